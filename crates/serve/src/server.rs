//! The thin adapter between hyper and the service, on the viewer's accept loop and limits
//! (whitted-view's `serve_connections`: request head size and time, connections at once, a
//! connection's lifetime), with its Host check and its reply body that hands hyper a chunk at
//! a time. A GET has no body (413 if it
//! announces one); an upload's body is refused whole before a byte is read when it announces
//! more than `MAX_BODY`, and is read through multer with the same limits otherwise, only after
//! the link was checked: a revoked or wrong link costs the server nothing.

use std::sync::Arc;

use futures_util::StreamExt;
use http_body_util::BodyStream;
use hyper::body::Incoming as Body;
use hyper::header::{HeaderValue, CONTENT_LENGTH, CONTENT_TYPE, HOST, TRANSFER_ENCODING};
use hyper::{Request, Response};

use super::answer::{self, Caller};
use super::images::stored_name;
use super::project::SOURCES;
use super::reply::Reply;
use super::route::{self, Route, StudentPage};
use super::store::{Kind, Student};
use super::upload::{self, Submission, MAX_BODY, MAX_FILE, MAX_FILES};
use super::{db, App};
use whitted_core::error::{Error, Result};
use whitted_view::held_body::HeldBody;
use whitted_view::{check_host, serve_connections, Limits};

/// Threads that answer from the database.
const BLOCKING: usize = 8;
/// Connections served at once: a class, not the viewer's one user. A browser keeps a few
/// connections open to a site, and each student's page polls its queued attempt, so the
/// viewer's 64 turned students away (503) at about 60 waiting at once. 512, with the 256
/// turned-away answers, stays inside a default limit of 1024 open files.
pub const CONNECTIONS: usize = 512;
/// Uploads a student may make in `RATE_WINDOW` seconds.
pub const RATE: i64 = 6;
pub const RATE_WINDOW: i64 = 60;

pub fn run(listener: std::net::TcpListener, app: Arc<App>) -> Result<()> {
    let service = move |request: Request<Body>, peer: std::net::IpAddr| {
        let app = app.clone();
        async move {
            let head = request.method() == hyper::Method::HEAD;
            let reply = handle(app, request, peer).await;
            response(reply, head)
        }
    };
    let limits = Limits {
        max_connections: CONNECTIONS,
        ..Limits::with_threads(BLOCKING)
    };
    serve_connections(listener, limits, || Ok(()), service)
}

async fn handle(app: Arc<App>, request: Request<Body>, peer: std::net::IpAddr) -> Reply {
    let headers = request.headers();
    let hosts: Vec<&[u8]> = headers
        .get_all(HOST)
        .iter()
        .map(HeaderValue::as_bytes)
        .collect();
    if let Err((status, _, message)) = check_host(
        request.uri().authority().map(|a| a.as_str()),
        &hosts,
        &app.hosts,
    ) {
        return Reply::refusal(status, &String::from_utf8_lossy(&message));
    }
    let route = match route::parse(request.method().as_str(), request.uri().path()) {
        Ok(route) => route,
        Err((status, message)) => return Reply::refusal(status, message),
    };
    let announced = headers
        .get(CONTENT_LENGTH)
        .map(|v| v.to_str().ok().and_then(|v| v.parse::<u64>().ok()));
    let has_body =
        announced.is_some_and(|n| n != Some(0)) || headers.contains_key(TRANSFER_ENCODING);
    if let Route::Student {
        number,
        secret,
        page: StudentPage::Upload,
    } = &route
    {
        return upload(app, request, *number, secret.clone(), announced.flatten()).await;
    }
    if has_body {
        return Reply::refusal(413, "a request for a page has no body");
    }
    let caller = Caller {
        peer,
        user: app.proxy.as_ref().and_then(|trust| {
            headers
                .get(trust.header.as_str())
                .and_then(|v| v.to_str().ok())
                .map(str::to_string)
        }),
    };
    let query = request.uri().query().unwrap_or("").to_string();
    tokio::task::spawn_blocking(move || answer::get(&app, &route, &caller, &query))
        .await
        .unwrap_or_else(|_| Reply::refusal(500, "internal error"))
}

/// Runs `f` on a blocking thread with the database.
async fn blocking<T: Send + 'static>(
    app: &Arc<App>,
    f: impl FnOnce(&App, &mut super::store::Store) -> Result<T> + Send + 'static,
) -> Result<T> {
    let app = app.clone();
    tokio::task::spawn_blocking(move || db::with(&app.data.database(), |s| f(&app, s)))
        .await
        .unwrap_or_else(|_| Err(Error::Environment("a database task stopped".into())))
}

/// A refusal of an upload, on the student's page so that they can try again.
fn refused(app: &App, me: &Student, status: u16, message: &str) -> Reply {
    let attempts = db::with(&app.data.database(), |s| s.attempts_of(me.number)).unwrap_or_default();
    answer::student_home(app, me, &attempts, status, Some(message))
}

async fn upload(
    app: Arc<App>,
    request: Request<Body>,
    number: i64,
    secret: String,
    announced: Option<u64>,
) -> Reply {
    let me = match blocking(&app, move |_, s| answer::student(s, number, &secret)).await {
        Ok(Ok(me)) => me,
        Ok(Err(refusal)) => return refusal,
        Err(e) => {
            eprintln!("whitted serve: {e}");
            return Reply::refusal(500, "the service could not answer; try again shortly");
        }
    };
    if announced.is_some_and(|n| n > MAX_BODY) {
        let message = format!("the upload is too large: at most {} MiB", MAX_BODY >> 20);
        return refused(&app, &me, 413, &message);
    }
    let headers = request.headers();
    if headers
        .get("sec-fetch-site")
        .is_some_and(|v| v.as_bytes() == b"cross-site")
    {
        return Reply::refusal(403, "forbidden: an upload from another site");
    }
    let boundary = headers
        .get(CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| multer::parse_boundary(v).ok());
    let Some(boundary) = boundary else {
        return Reply::refusal(400, "bad request: an upload is the page's multipart form");
    };
    let stream = BodyStream::new(request.into_body()).filter_map(|frame| async move {
        match frame {
            Ok(frame) => frame.into_data().ok().map(Ok),
            Err(e) => Some(Err(e)),
        }
    });
    let constraints = multer::Constraints::new()
        .allowed_fields(vec!["csrf", "files", "scene"])
        .size_limit(
            multer::SizeLimit::new()
                .whole_stream(MAX_BODY)
                .per_field(MAX_FILE)
                .for_field("csrf", 64)
                .for_field("scene", 64),
        );
    let mut multipart = multer::Multipart::with_constraints(stream, boundary, constraints);
    let mut csrf_ok = false;
    let mut files = Vec::new();
    // The scene chosen for each file: a select follows the file input of its row.
    let mut scenes: Vec<Option<String>> = Vec::new();
    loop {
        let field = match multipart.next_field().await {
            Ok(Some(field)) => field,
            Ok(None) => break,
            Err(e) => return refused(&app, &me, 413.min(status_of(&e)), &upload_error(&e)),
        };
        match field.name() {
            Some("csrf") => {
                let given = field.text().await.unwrap_or_default();
                csrf_ok = super::secret::same(&given, &me.csrf);
                if !csrf_ok {
                    return Reply::refusal(
                        403,
                        "forbidden: the form is stale or forged; reload the page",
                    );
                }
            }
            _ if !csrf_ok => {
                return Reply::refusal(
                    403,
                    "forbidden: the form is stale or forged; reload the page",
                )
            }
            Some("scene") => {
                let value = field.text().await.unwrap_or_default();
                for unset in scenes.iter_mut().rev().take_while(|s| s.is_none()) {
                    *unset = Some(value.clone());
                }
            }
            _ => {
                if files.len() == MAX_FILES {
                    return refused(
                        &app,
                        &me,
                        413,
                        &format!("at most {MAX_FILES} files at once"),
                    );
                }
                let name = field.file_name().unwrap_or("").to_string();
                match field.bytes().await {
                    Ok(bytes) => {
                        files.push((name, bytes.to_vec()));
                        scenes.push(None);
                    }
                    Err(e) => return refused(&app, &me, status_of(&e), &upload_error(&e)),
                }
            }
        }
    }
    if !csrf_ok {
        return Reply::refusal(
            403,
            "forbidden: the form is stale or forged; reload the page",
        );
    }
    let scenes: Vec<Option<String>> = files
        .iter()
        .zip(scenes)
        .filter(|((name, _), _)| !name.is_empty())
        .map(|(_, scene)| scene)
        .collect();
    let mut choices = Vec::new();
    for scene in scenes {
        match scene {
            None => choices.push(None),
            Some(v) => match super::scene_choice::parse(&v, app.course) {
                Some(_) => choices.push(Some(v)),
                None => return refused(&app, &me, 422, "choose each image's scene from the list"),
            },
        }
    }
    let submission = match upload::classify(files) {
        Ok(s) => s,
        Err(why) => return refused(&app, &me, 422, &why),
    };
    let number = me.number;
    let kept = blocking(&app, move |app, store| {
        keep(app, store, number, submission, &choices)
    })
    .await;
    match kept {
        Ok(Ok(id)) => {
            app.bell.ring();
            Reply::see_other(format!(
                "/s/{}-{}/attempt/{id}",
                me.number,
                me.secret.as_deref().unwrap_or("")
            ))
        }
        Ok(Err(why)) => refused(&app, &me, 429, &why),
        Err(e) => {
            eprintln!("whitted serve: {e}");
            Reply::refusal(500, "the upload could not be kept; try again shortly")
        }
    }
}

fn status_of(e: &multer::Error) -> u16 {
    match e {
        multer::Error::StreamSizeExceeded { .. } | multer::Error::FieldSizeExceeded { .. } => 413,
        _ => 400,
    }
}

fn upload_error(e: &multer::Error) -> String {
    match e {
        multer::Error::StreamSizeExceeded { .. } => {
            format!("the upload is too large: at most {} MiB", MAX_BODY >> 20)
        }
        multer::Error::FieldSizeExceeded { .. } => {
            format!("a file is too large: at most {} MiB", MAX_FILE >> 20)
        }
        multer::Error::UnknownField { .. } => "the upload is not the page's form".into(),
        _ => "the upload was cut short or is malformed; try again".into(),
    }
}

/// Applies the rate limit, then keeps the files and records the attempt; the attempt's id,
/// or the sentence of the refusal.
fn keep(
    app: &App,
    store: &mut super::store::Store,
    student: i64,
    submission: Submission,
    choices: &[Option<String>],
) -> Result<std::result::Result<i64, String>> {
    let (recent, project_pending) = store.recent(student, super::store::now() - RATE_WINDOW)?;
    if recent >= RATE {
        return Ok(Err(format!(
            "too many uploads: at most {RATE} a minute; wait a minute and try again"
        )));
    }
    let receiving = app.data.receive()?;
    let (kind, names) = match submission {
        Submission::Images(images) => {
            for (i, (_, bytes)) in images.iter().enumerate() {
                receiving.write(&stored_name(i), bytes)?;
                if let Some(Some(choice)) = choices.get(i) {
                    receiving.write(&super::scene_choice::stored_name(i), choice.as_bytes())?;
                }
            }
            (
                Kind::Images,
                images.into_iter().map(|(n, _)| n).collect::<Vec<_>>(),
            )
        }
        Submission::Project(sources) => {
            if project_pending {
                return Ok(Err(
                    "your previous project is still queued or running: wait for its result".into(),
                ));
            }
            let dir = receiving.path().join(SOURCES);
            std::fs::create_dir(&dir).map_err(|e| Error::io(&dir, "cannot create", e))?;
            for (name, bytes) in &sources {
                receiving.write(&format!("{SOURCES}/{name}"), bytes)?;
            }
            (Kind::Project, sources.into_iter().map(|(n, _)| n).collect())
        }
    };
    let names: Vec<String> = names.iter().map(|n| n.replace('\n', " ")).collect();
    let folder = receiving.keep()?;
    Ok(Ok(store.add_attempt(
        student,
        kind,
        &folder,
        &names.join("\n"),
    )?))
}

/// A reply as hyper wants it (without its body for a HEAD request).
fn response(reply: Reply, head: bool) -> Response<HeldBody> {
    let headers = reply.headers();
    let body = if head { Vec::new() } else { reply.body };
    let mut response = Response::new(HeldBody::new(body, None));
    *response.status_mut() = hyper::StatusCode::from_u16(reply.status)
        .unwrap_or(hyper::StatusCode::INTERNAL_SERVER_ERROR);
    for (name, value) in headers {
        response.headers_mut().insert(name, value);
    }
    response
}
