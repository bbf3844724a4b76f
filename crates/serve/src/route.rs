//! Every request the service answers, parsed before any work into a closed set, or refused.
//! Pure, so that each hostile path is a unit test. Who may see what (the secrets, the
//! attempts' owners) is decided after, against the database (`answer.rs`).

/// A parsed request.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Route {
    /// `/`: a page that says to open one's personal link.
    Home,
    /// The pages' own script and style: no inline script anywhere (the CSP forbids it).
    Asset(Asset),
    /// `/s/<number>-<secret>/...`: a student's pages.
    Student {
        number: i64,
        secret: String,
        page: StudentPage,
    },
    /// `/staff/<secret>/...`, or `/staff/proxy/...` for a user the trusted proxy names.
    Staff { key: StaffKey, page: StaffPage },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Asset {
    Script,
    Style,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StudentPage {
    Home,
    /// POST: a multipart upload of images or a project.
    Upload,
    Attempt(i64),
    /// The attempt's state as JSON, which the attempt page polls.
    Status(i64),
    /// The attempt's report, as `check --report x.html` writes it.
    Report(i64),
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StaffKey {
    Secret(String),
    /// The user the trusted proxy's header names (`--trust-user-header`).
    Proxy,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StaffPage {
    Class,
    /// One student's history, by their number.
    Student(i64),
    Attempt(i64),
    Status(i64),
    Report(i64),
    Export(Export),
}

/// What the staff can export of the latest attempts, as `whitted grade` writes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Export {
    /// Moodle's grading worksheet (`moodle.csv`).
    Worksheet,
    ClassCsv,
    FeedbackZip,
}

impl Export {
    pub fn file_name(self) -> &'static str {
        match self {
            Export::Worksheet => "moodle.csv",
            Export::ClassCsv => "class.csv",
            Export::FeedbackZip => "feedback.zip",
        }
    }
}

/// A refusal: status and message.
pub type Refusal = (u16, &'static str);

const NOT_FOUND: Refusal = (404, "not found");

/// Parses `method` `path` (undecoded; the service's paths need no decoding).
pub fn parse(method: &str, path: &str) -> Result<Route, Refusal> {
    let post = match method {
        "GET" | "HEAD" => false,
        "POST" => true,
        _ => return Err((405, "method not allowed")),
    };
    let parts: Vec<&str> = path
        .strip_prefix('/')
        .ok_or(NOT_FOUND)?
        .split('/')
        .collect();
    let route = match parts.as_slice() {
        [""] => Route::Home,
        ["app.js"] => Route::Asset(Asset::Script),
        ["style.css"] => Route::Asset(Asset::Style),
        ["s", key, rest @ ..] => {
            let (number, secret) = key.split_once('-').ok_or(NOT_FOUND)?;
            let number = id(number)?;
            let secret = hex(secret)?;
            let page = match rest {
                [] | [""] => StudentPage::Home,
                ["upload"] => StudentPage::Upload,
                ["attempt", n] => StudentPage::Attempt(id(n)?),
                ["attempt", n, "status"] => StudentPage::Status(id(n)?),
                ["attempt", n, "report"] => StudentPage::Report(id(n)?),
                _ => return Err(NOT_FOUND),
            };
            Route::Student {
                number,
                secret,
                page,
            }
        }
        ["staff", key, rest @ ..] => {
            let key = match *key {
                "proxy" => StaffKey::Proxy,
                secret => StaffKey::Secret(hex(secret)?),
            };
            let page = match rest {
                [] | [""] => StaffPage::Class,
                ["student", n] => StaffPage::Student(id(n)?),
                ["attempt", n] => StaffPage::Attempt(id(n)?),
                ["attempt", n, "status"] => StaffPage::Status(id(n)?),
                ["attempt", n, "report"] => StaffPage::Report(id(n)?),
                ["export", "moodle.csv"] => StaffPage::Export(Export::Worksheet),
                ["export", "class.csv"] => StaffPage::Export(Export::ClassCsv),
                ["export", "feedback.zip"] => StaffPage::Export(Export::FeedbackZip),
                _ => return Err(NOT_FOUND),
            };
            Route::Staff { key, page }
        }
        _ => return Err(NOT_FOUND),
    };
    let wants_post = matches!(
        route,
        Route::Student {
            page: StudentPage::Upload,
            ..
        }
    );
    match (post, wants_post) {
        (false, false) | (true, true) => Ok(route),
        (true, false) => Err((405, "method not allowed: this page is read with GET")),
        (false, true) => Err((
            405,
            "method not allowed: an upload is a POST of the page's form",
        )),
    }
}

/// A row number: digits, at most 18 of them.
fn id(text: &str) -> Result<i64, Refusal> {
    match !text.is_empty() && text.len() <= 18 && text.bytes().all(|b| b.is_ascii_digit()) {
        true => text.parse().map_err(|_| NOT_FOUND),
        false => Err(NOT_FOUND),
    }
}

/// A secret: 32 lowercase hex digits.
fn hex(text: &str) -> Result<String, Refusal> {
    match text.len() == 32 && text.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f')) {
        true => Ok(text.to_string()),
        false => Err(NOT_FOUND),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const S: &str = "0123456789abcdef0123456789abcdef";

    #[test]
    fn the_closed_set_is_parsed() {
        let student = |page| Route::Student {
            number: 7,
            secret: S.into(),
            page,
        };
        assert_eq!(parse("GET", "/"), Ok(Route::Home));
        assert_eq!(parse("GET", "/app.js"), Ok(Route::Asset(Asset::Script)));
        assert_eq!(
            parse("GET", &format!("/s/7-{S}")),
            Ok(student(StudentPage::Home))
        );
        assert_eq!(
            parse("POST", &format!("/s/7-{S}/upload")),
            Ok(student(StudentPage::Upload))
        );
        assert_eq!(
            parse("HEAD", &format!("/s/7-{S}/attempt/12/status")),
            Ok(student(StudentPage::Status(12)))
        );
        assert_eq!(
            parse("GET", &format!("/staff/{S}/export/feedback.zip")),
            Ok(Route::Staff {
                key: StaffKey::Secret(S.into()),
                page: StaffPage::Export(Export::FeedbackZip)
            })
        );
        assert_eq!(
            parse("GET", "/staff/proxy/student/3"),
            Ok(Route::Staff {
                key: StaffKey::Proxy,
                page: StaffPage::Student(3)
            })
        );
    }

    #[test]
    fn hostile_and_malformed_paths_are_refused_before_any_work() {
        for (method, path, status) in [
            ("GET", "/s/7-short", 404),
            ("GET", &format!("/s/7-{}", S.to_uppercase()), 404),
            ("GET", &format!("/s/-1-{S}"), 404),
            ("GET", &format!("/s/7-{S}/../../staff"), 404),
            ("GET", &format!("/s/7-{S}/attempt/..%2f1"), 404),
            (
                "GET",
                &format!("/s/7-{S}/attempt/99999999999999999999"),
                404,
            ),
            ("GET", &format!("/s/7-{S}/upload"), 405),
            ("POST", &format!("/s/7-{S}"), 405),
            ("DELETE", &format!("/s/7-{S}"), 405),
            ("GET", "/staff/proxy/export/../../db", 404),
            ("GET", "/uploads/a-1/image-1.png", 404),
            ("GET", "//etc/passwd", 404),
            ("GET", "", 404),
        ] {
            assert_eq!(
                parse(method, path).map_err(|r| r.0),
                Err(status),
                "{method} {path}"
            );
        }
    }
}
