//! A viewer request, parsed and checked before any work: the closed set of what the page asks
//! for, or the refusal (status and message) for anything else. Pure, so that every hostile
//! request is a unit test.

use super::planes::Which;
use super::Reply;

/// Everything the viewer answers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ApiRequest {
    /// The page itself.
    Page,
    /// The image's size, layers and lights, and what else there is (JSON).
    Image,
    /// How many times the files were (re)loaded, and the last reload's failure; while the
    /// first load runs, what it reads (JSON).
    Version,
    /// The check's report (JSON), in check mode.
    Check,
    /// One layer's values, every `step`-th pixel of every `step`-th row: the whole layer, or
    /// one `TILE` x `TILE` tile of those samples.
    Layer {
        which: Which,
        name: String,
        step: usize,
        tile: Option<(usize, usize)>,
    },
    /// A layer's statistics and histogram (JSON).
    Stats { which: Which, name: String },
    /// Every layer's values at one pixel, the image's and the reference's (JSON).
    Pixel { x: usize, y: usize },
    /// One pixel's ray trees: the reference's and the top mistake's (JSON).
    Trees { x: usize, y: usize },
}

impl ApiRequest {
    /// Whether the answer needs what the files hold (the page and the version do not: they
    /// answer while the first load runs).
    pub fn needs_content(&self) -> bool {
        !matches!(self, ApiRequest::Page | ApiRequest::Version)
    }

    /// Whether the answer can take most of a second (a whole layer, statistics over every
    /// pixel, a hierarchy rebuilt for the trees): those take turns (`admission.rs`) so that
    /// the others never queue behind them. A tile is bounded by `TILE` and stays cheap.
    pub fn is_heavy(&self) -> bool {
        match self {
            ApiRequest::Layer { tile, .. } => tile.is_none(),
            ApiRequest::Stats { .. } | ApiRequest::Trees { .. } => true,
            ApiRequest::Page
            | ApiRequest::Image
            | ApiRequest::Version
            | ApiRequest::Check
            | ApiRequest::Pixel { .. } => false,
        }
    }
}

/// The parts of an HTTP request the viewer looks at, as the server library hands them over.
#[derive(Debug, Clone)]
pub struct Incoming<'a> {
    pub method: &'a str,
    /// The path, undecoded.
    pub path: &'a str,
    /// The query, undecoded (`a=1&b=%20`), empty when there is none.
    pub query: &'a str,
    /// Every `Host` header's value.
    pub hosts: Vec<&'a [u8]>,
    /// The authority of an absolute-form target (`GET http://host:port/path`), if it has one:
    /// it stands for the Host header then (RFC 9112 3.2.2).
    pub authority: Option<&'a str>,
    /// Whether the request announces a body (`Content-Length` > 0 or `Transfer-Encoding`).
    pub has_body: bool,
}

/// The largest `step` asked for: past the image's size every step gives one pixel.
const MAX_STEP: usize = 1 << 16;

fn refuse(status: u16, message: &str) -> Reply {
    super::text(status, message)
}

/// Refuses a request whose Host (or absolute-form authority, RFC 9112 3.2.2) is not one of
/// `allowed` (DNS rebinding): 400 for no or several Host headers, 403 for another name.
pub fn check_host(
    authority: Option<&str>,
    hosts: &[&[u8]],
    allowed: &[String],
) -> Result<(), Reply> {
    let host = match (authority, hosts) {
        (Some(authority), _) => authority.as_bytes(),
        (None, [host]) => *host,
        (None, []) => return Err(refuse(400, "bad request: no Host header")),
        (None, _) => return Err(refuse(400, "bad request: more than one Host header")),
    };
    if !allowed.iter().any(|a| a.as_bytes() == host) {
        return Err(refuse(
            403,
            "forbidden: not an address this server answers as",
        ));
    }
    Ok(())
}

/// Checks and parses `request` for the viewer listening on 127.0.0.1:`port` with `token`:
/// 405 for a method other than GET or HEAD; 400 for no or several Host headers; 403 for a
/// Host that is not this loopback address (DNS rebinding) or a missing or wrong token; 413 for
/// a body; 404 for any other path; 400 for a malformed parameter.
pub fn parse(request: &Incoming, token: &str, port: u16) -> Result<ApiRequest, Reply> {
    if request.method != "GET" && request.method != "HEAD" {
        return Err(refuse(
            405,
            "method not allowed: the viewer answers GET and HEAD",
        ));
    }
    let allowed = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    check_host(request.authority, &request.hosts, &allowed)?;
    if request.has_body {
        return Err(refuse(413, "a request to the viewer has no body"));
    }
    let params: Vec<(String, String)> = form_urlencoded::parse(request.query.as_bytes())
        .map(|(k, v)| (k.into_owned(), v.into_owned()))
        .collect();
    let param = |key: &str| {
        params
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    };
    if param("token") != Some(token) {
        return Err(refuse(403, "forbidden: missing or wrong token"));
    }
    let number = |key: &str| -> Result<Option<usize>, Reply> {
        match param(key) {
            None => Ok(None),
            Some(v) => v
                .parse::<usize>()
                .map(Some)
                .map_err(|_| refuse(400, &format!("bad request: `{key}` must be a whole number"))),
        }
    };
    let which = || match param("which") {
        None => Ok(Which::Main),
        Some(name) => Which::from_name(name).ok_or_else(|| {
            refuse(
                400,
                "bad request: `which` is main, reference or an error metric",
            )
        }),
    };
    let name = || -> Result<String, Reply> {
        Ok(param("name")
            .ok_or_else(|| refuse(400, "bad request: `name` is missing"))?
            .to_string())
    };
    let pixel = || match (number("x")?, number("y")?) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => Err(refuse(400, "bad request: `x` and `y` are needed")),
    };
    match request.path {
        "/" => Ok(ApiRequest::Page),
        "/api/image" => Ok(ApiRequest::Image),
        "/api/version" => Ok(ApiRequest::Version),
        "/api/check" => Ok(ApiRequest::Check),
        "/api/layer" => {
            let (which, name) = (which()?, name()?);
            let step = number("step")?.unwrap_or(1);
            if step == 0 || step > MAX_STEP {
                return Err(refuse(400, "bad request: `step` is from 1 to 65536"));
            }
            let tile = match (number("tx")?, number("ty")?) {
                (Some(tx), Some(ty)) => Some((tx, ty)),
                (None, None) => None,
                _ => return Err(refuse(400, "bad request: a tile needs `tx` and `ty`")),
            };
            Ok(ApiRequest::Layer {
                which,
                name,
                step,
                tile,
            })
        }
        "/api/stats" => Ok(ApiRequest::Stats {
            which: which()?,
            name: name()?,
        }),
        "/api/pixel" => pixel().map(|(x, y)| ApiRequest::Pixel { x, y }),
        "/api/trees" => pixel().map(|(x, y)| ApiRequest::Trees { x, y }),
        _ => Err(refuse(404, "not found")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOKEN: &str = "0123abcd";

    fn get(target: &str) -> Result<ApiRequest, u16> {
        let (path, query) = target.split_once('?').unwrap_or((target, ""));
        let request = Incoming {
            method: "GET",
            path,
            query,
            hosts: vec![b"127.0.0.1:8000"],
            authority: None,
            has_body: false,
        };
        parse(&request, TOKEN, 8000).map_err(|r| r.0)
    }

    #[test]
    fn the_closed_set_of_requests_is_parsed() {
        assert_eq!(get("/?token=0123abcd"), Ok(ApiRequest::Page));
        assert_eq!(
            get("/api/layer?name=light_a%20b%26%3D%2B%23%25%2F%3F%C3%A9&token=0123abcd&step=4"),
            Ok(ApiRequest::Layer {
                which: Which::Main,
                name: "light_a b&=+#%/?é".into(),
                step: 4,
                tile: None,
            })
        );
        assert_eq!(
            get("/api/layer?name=beauty&which=relative-squared-error&tx=2&ty=0&token=0123abcd"),
            Ok(ApiRequest::Layer {
                which: Which::Metric(super::super::metric::Metric::RelativeSquaredError),
                name: "beauty".into(),
                step: 1,
                tile: Some((2, 0)),
            })
        );
        assert_eq!(
            get("/api/stats?name=Z&which=reference&token=0123abcd"),
            Ok(ApiRequest::Stats {
                which: Which::Reference,
                name: "Z".into(),
            })
        );
        assert_eq!(
            get("/api/trees?x=1&y=2&token=0123abcd"),
            Ok(ApiRequest::Trees { x: 1, y: 2 })
        );
        for path in ["/api/version", "/api/check"] {
            assert!(get(&format!("{path}?token=0123abcd")).is_ok(), "{path}");
            assert_eq!(get(path), Err(403), "{path} without the token");
        }
        assert_eq!(
            get("/api/pixel?x=3&y=4&token=0123abcd"),
            Ok(ApiRequest::Pixel { x: 3, y: 4 })
        );
    }

    #[test]
    fn malformed_and_hostile_requests_are_refused_before_any_work() {
        for (target, status) in [
            ("/", 403),
            ("/?token=wrong", 403),
            ("/nowhere?token=0123abcd", 404),
            ("/api/layer?token=0123abcd", 400),
            ("/api/layer?name=direct&step=x&token=0123abcd", 400),
            ("/api/layer?name=direct&step=0&token=0123abcd", 400),
            (
                "/api/layer?name=direct&step=99999999999999999999&token=0123abcd",
                400,
            ),
            ("/api/layer?name=direct&which=other&token=0123abcd", 400),
            ("/api/pixel?x=-1&y=0&token=0123abcd", 400),
            ("/api/pixel?token=0123abcd", 400),
            ("/api/trees?x=1&token=0123abcd", 400),
            ("/api/trees?x=1&y=1e3&token=0123abcd", 400),
            ("/api/stats?token=0123abcd", 400),
            ("/api/stats?name=beauty&which=mse&token=0123abcd", 400),
            ("/api/layer?name=beauty&tx=1&token=0123abcd", 400),
            ("/api/layer?name=beauty&tx=1&ty=-1&token=0123abcd", 400),
        ] {
            assert_eq!(get(target), Err(status), "{target}");
        }
        let base = Incoming {
            method: "GET",
            path: "/",
            query: "token=0123abcd",
            hosts: vec![b"127.0.0.1:8000"],
            authority: None,
            has_body: false,
        };
        let status = |r: Incoming| parse(&r, TOKEN, 8000).map_err(|r| r.0).err();
        for method in ["POST", "PUT", "DELETE", "OPTIONS", "BREW"] {
            assert_eq!(
                status(Incoming {
                    method,
                    ..base.clone()
                }),
                Some(405),
                "{method}"
            );
        }
        assert_eq!(
            status(Incoming {
                method: "HEAD",
                ..base.clone()
            }),
            None
        );
        let two = vec![&b"127.0.0.1:8000"[..], b"127.0.0.1:8000"];
        assert_eq!(
            status(Incoming {
                hosts: two,
                ..base.clone()
            }),
            Some(400)
        );
        assert_eq!(
            status(Incoming {
                hosts: vec![],
                ..base.clone()
            }),
            Some(400)
        );
        let evil = vec![&b"evil.example:8000"[..]];
        assert_eq!(
            status(Incoming {
                hosts: evil.clone(),
                ..base.clone()
            }),
            Some(403)
        );
        // An absolute-form target's authority stands for Host (RFC 9112 3.2.2): a foreign
        // one is refused whatever Host says, ours is served whatever Host says.
        assert_eq!(
            status(Incoming {
                authority: Some("evil.example"),
                ..base.clone()
            }),
            Some(403)
        );
        assert_eq!(
            status(Incoming {
                authority: Some("127.0.0.1:8000"),
                hosts: evil,
                ..base.clone()
            }),
            None
        );
        assert_eq!(
            status(Incoming {
                has_body: true,
                ..base
            }),
            Some(413)
        );
    }
}
