//! A reply and the headers every reply carries: a Content-Security-Policy with no inline
//! script (the service's pages), or none at all (a check report, which is shown sandboxed:
//! inline style and data: images only, no script at all), no caching, no sniffing, no referrer (the links carry
//! secrets), framed by the service's own pages only.

use hyper::header::{HeaderName, HeaderValue};

/// Which policy a reply's content is served under.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Policy {
    /// The service's pages, its script and style, JSON, downloads.
    Page,
    /// A check's report page (inline style, embedded images, no script).
    Report,
}

impl Policy {
    pub fn csp(self) -> &'static str {
        match self {
            Policy::Page => {
                "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; \
                 connect-src 'self'; frame-src 'self'; form-action 'self'; \
                 frame-ancestors 'none'; base-uri 'none'"
            }
            Policy::Report => {
                "default-src 'none'; style-src 'unsafe-inline'; img-src data:; \
                 frame-ancestors 'self'; base-uri 'none'; form-action 'none'"
            }
        }
    }
}

#[derive(Debug, Clone)]
pub struct Reply {
    pub status: u16,
    pub kind: &'static str,
    pub body: Vec<u8>,
    pub policy: Policy,
    /// A redirect's target (303 after an upload).
    pub location: Option<String>,
    /// A download's file name.
    pub download: Option<&'static str>,
}

impl Reply {
    pub fn html(status: u16, page: String) -> Reply {
        Reply {
            status,
            kind: "text/html; charset=utf-8",
            body: page.into_bytes(),
            policy: Policy::Page,
            location: None,
            download: None,
        }
    }

    pub fn report(page: String) -> Reply {
        Reply {
            policy: Policy::Report,
            ..Reply::html(200, page)
        }
    }

    pub fn json(value: &serde_json::Value) -> Reply {
        Reply {
            kind: "application/json",
            body: value.to_string().into_bytes(),
            ..Reply::html(200, String::new())
        }
    }

    pub fn bytes(kind: &'static str, body: Vec<u8>) -> Reply {
        Reply {
            kind,
            body,
            ..Reply::html(200, String::new())
        }
    }

    /// A refusal as a page: status and the one sentence.
    pub fn refusal(status: u16, message: &str) -> Reply {
        Reply::html(status, super::pages::refusal(message))
    }

    pub fn see_other(location: String) -> Reply {
        Reply {
            location: Some(location),
            ..Reply::html(303, String::new())
        }
    }

    /// The headers, beside the content type.
    pub fn headers(&self) -> Vec<(HeaderName, HeaderValue)> {
        let mut headers = vec![
            (
                hyper::header::CONTENT_TYPE,
                HeaderValue::from_static(self.kind),
            ),
            (
                hyper::header::CONTENT_SECURITY_POLICY,
                HeaderValue::from_static(self.policy.csp()),
            ),
            (
                hyper::header::CACHE_CONTROL,
                HeaderValue::from_static("no-store"),
            ),
            (
                hyper::header::X_CONTENT_TYPE_OPTIONS,
                HeaderValue::from_static("nosniff"),
            ),
            (
                hyper::header::REFERRER_POLICY,
                HeaderValue::from_static("no-referrer"),
            ),
        ];
        if let Some(value) = self
            .location
            .as_deref()
            .and_then(|l| HeaderValue::from_str(l).ok())
        {
            headers.push((hyper::header::LOCATION, value));
        }
        if let Some(name) = self.download {
            if let Ok(value) = HeaderValue::from_str(&format!("attachment; filename=\"{name}\"")) {
                headers.push((hyper::header::CONTENT_DISPOSITION, value));
            }
        }
        headers
    }
}
