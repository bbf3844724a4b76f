//! Answers a parsed request against the database: who the link or the proxy says the caller
//! is, and what they may see. A student reaches their own attempts only: an attempt of
//! another student is answered exactly as one that does not exist (404), so that a URL tells
//! nothing. A revoked link is refused with a sentence that says what to do.

use std::net::IpAddr;

use serde_json::json;

use super::reply::Reply;
use super::route::{Asset, Route, StaffKey, StaffPage, StudentPage};
use super::staff_view::ClassView;
use super::store::{now, Attempt, Status, Store, Student};
use super::{db, export, pages, secret, App};
use whitted_core::error::Result;

/// Who made the request, beside its path: the peer, and the user header's value.
pub struct Caller {
    pub peer: IpAddr,
    pub user: Option<String>,
}

pub const REVOKED: &str = "this link was revoked: ask the course staff for your new link";
const NOT_FOUND: &str = "not found";

/// The reply to a GET (or HEAD) of `route`.
pub fn get(app: &App, route: &Route, caller: &Caller, query: &str) -> Reply {
    let answer = db::with(&app.data.database(), |store| match route {
        Route::Home => Ok(Reply::html(200, pages::home())),
        Route::Asset(Asset::Script) => Ok(Reply::bytes("text/javascript", pages::SCRIPT.into())),
        Route::Asset(Asset::Style) => Ok(Reply::bytes("text/css", pages::STYLE.into())),
        Route::Student {
            number,
            secret,
            page,
        } => match student(store, *number, secret)? {
            Err(refusal) => Ok(refusal),
            Ok(me) => student_page(app, store, &me, page, query),
        },
        Route::Staff { key, page } => match staff(app, store, key, caller)? {
            Err(refusal) => Ok(refusal),
            Ok(base) => staff_page(app, store, &base, page, query),
        },
    });
    answer.unwrap_or_else(|e| {
        eprintln!("whitted serve: {e}");
        Reply::refusal(500, "the service could not answer; try again shortly")
    })
}

/// The student a link names, or the refusal (403 for a wrong secret or a revoked link).
pub fn student(
    store: &Store,
    number: i64,
    given: &str,
) -> Result<std::result::Result<Student, Reply>> {
    let found = store.student(number)?;
    Ok(match found {
        Some(s) => match &s.secret {
            Some(expected) if secret::same(given, expected) => Ok(s),
            Some(_) => Err(Reply::refusal(403, "this link is not valid")),
            None => Err(Reply::refusal(403, REVOKED)),
        },
        None => {
            // As long as a comparison would have taken.
            secret::same(given, "00000000000000000000000000000000");
            Err(Reply::refusal(403, "this link is not valid"))
        }
    })
}

/// The base of the staff's URLs, when the caller is staff; or the refusal.
fn staff(
    app: &App,
    store: &Store,
    key: &StaffKey,
    caller: &Caller,
) -> Result<std::result::Result<String, Reply>> {
    Ok(match key {
        StaffKey::Secret(given) => {
            let (expected, _) = store.staff()?;
            match secret::same(given, &expected) {
                true => Ok(format!("/staff/{given}")),
                false => Err(Reply::refusal(403, "this link is not valid")),
            }
        }
        StaffKey::Proxy => match (&app.proxy, &caller.user) {
            (Some(trust), Some(user))
                if caller.peer == trust.proxy && trust.staff.contains(user) =>
            {
                Ok("/staff/proxy".into())
            }
            _ => Err(Reply::refusal(
                403,
                "forbidden: not signed in as one of the staff",
            )),
        },
    })
}

/// The attempt `id` when it is `student`'s (None: no such attempt, as far as they know).
fn own_attempt(store: &Store, student: Option<i64>, id: i64) -> Result<Option<Attempt>> {
    Ok(store
        .attempt(id)?
        .filter(|a| student.is_none_or(|s| a.student == s)))
}

/// The student's home page with `attempts` (and `message`, an upload's refusal), built in one
/// place so that a refused upload shows the same page, tick and scene choices as a visit.
pub(super) fn student_home(
    app: &App,
    me: &Student,
    attempts: &[Attempt],
    status: u16,
    message: Option<&str>,
) -> Reply {
    let base = student_base(me);
    let tick = whitted_grade::tick(app.course);
    let cases = super::scene_choice::cases(app.course);
    Reply::html(
        status,
        pages::student(&base, me, &tick, &cases, attempts, message),
    )
}

/// The path of `me`'s pages.
fn student_base(me: &Student) -> String {
    format!("/s/{}-{}", me.number, me.secret.as_deref().unwrap_or(""))
}

fn student_page(
    app: &App,
    store: &Store,
    me: &Student,
    page: &StudentPage,
    query: &str,
) -> Result<Reply> {
    let base = student_base(me);
    match page {
        StudentPage::Home => Ok(student_home(
            app,
            me,
            &store.attempts_of(me.number)?,
            200,
            None,
        )),
        StudentPage::Upload => Ok(Reply::refusal(405, "an upload is a POST")),
        StudentPage::Attempt(id) | StudentPage::Status(id) | StudentPage::Report(id) => {
            let Some(attempt) = own_attempt(store, Some(me.number), *id)? else {
                return Ok(Reply::refusal(404, NOT_FOUND));
            };
            Ok(attempt_reply(
                app,
                store,
                &base,
                &base,
                &attempt,
                page_kind(page),
                query,
            )?)
        }
    }
}

/// Which of an attempt's three replies is asked for.
#[derive(Clone, Copy)]
enum Part {
    Page,
    Status,
    Report,
}

fn page_kind(page: &StudentPage) -> Part {
    match page {
        StudentPage::Status(_) => Part::Status,
        StudentPage::Report(_) => Part::Report,
        _ => Part::Page,
    }
}

fn attempt_reply(
    app: &App,
    store: &Store,
    base: &str,
    back: &str,
    attempt: &Attempt,
    part: Part,
    query: &str,
) -> Result<Reply> {
    let reports: Vec<String> = attempt
        .outcome
        .as_ref()
        .and_then(|o| serde_json::from_str(&o.report).ok())
        .unwrap_or_default();
    Ok(match part {
        Part::Page => {
            let ordinal = store
                .attempts_of(attempt.student)?
                .iter()
                .filter(|a| a.id <= attempt.id)
                .count();
            Reply::html(
                200,
                pages::attempt(base, back, attempt, ordinal, reports.len()),
            )
        }
        Part::Status => Reply::json(&status_json(app, store, attempt)?),
        Part::Report => {
            let n: usize = form_urlencoded::parse(query.as_bytes())
                .find(|(k, _)| k == "n")
                .and_then(|(_, v)| v.parse().ok())
                .unwrap_or(0);
            match reports.into_iter().nth(n) {
                Some(page) => Reply::report(page),
                None => Reply::refusal(404, NOT_FOUND),
            }
        }
    })
}

/// What the attempt page polls: the state, the queue position, what runs and for how long;
/// for a project, the step its run is at (compiling, case k of n and its name, checking) and,
/// with `--slurm`, its job; once done, the CPU time its run took.
fn status_json(app: &App, store: &Store, attempt: &Attempt) -> Result<serde_json::Value> {
    let position = match attempt.status {
        Status::Queued => store.position(attempt)?,
        _ => 0,
    };
    let what = match attempt.kind {
        super::store::Kind::Images => "checking the images",
        super::store::Kind::Project => "compiling and running the course's scenes in the sandbox",
    };
    let step = match (attempt.status, attempt.kind) {
        (Status::Running, super::store::Kind::Project) => {
            super::job::progress(&app.data.upload(&attempt.folder))
        }
        _ => None,
    };
    let job = attempt.job.as_ref().map(|id| {
        let state = app
            .job_states
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(id)
            .cloned();
        json!({ "id": id, "state": state })
    });
    Ok(json!({
        "status": attempt.status.name(),
        "position": position,
        "what": what,
        "step": step,
        "job": job,
        "seconds": attempt
            .started
            .map_or(0, |s| (attempt.finished.unwrap_or_else(now) - s).max(0)),
        "passed": attempt.outcome.as_ref().map(|o| o.passed),
        "cpu_seconds": attempt.cpu,
    }))
}

fn staff_page(
    app: &App,
    store: &Store,
    base: &str,
    page: &StaffPage,
    query: &str,
) -> Result<Reply> {
    let tick = whitted_grade::tick(app.course);
    match page {
        StaffPage::Class => {
            let view = ClassView::of(store.students()?, &store.all_attempts()?, now());
            Ok(Reply::html(200, pages::class(base, &view, &tick)))
        }
        StaffPage::Student(number) => match store.student(*number)? {
            None => Ok(Reply::refusal(404, NOT_FOUND)),
            Some(s) => Ok(Reply::html(
                200,
                pages::history(base, &s, &store.attempts_of(s.number)?),
            )),
        },
        StaffPage::Attempt(id) | StaffPage::Status(id) | StaffPage::Report(id) => {
            let Some(attempt) = own_attempt(store, None, *id)? else {
                return Ok(Reply::refusal(404, NOT_FOUND));
            };
            let part = match page {
                StaffPage::Status(_) => Part::Status,
                StaffPage::Report(_) => Part::Report,
                _ => Part::Page,
            };
            let back = format!("{base}/student/{}", attempt.student);
            attempt_reply(app, store, base, &back, &attempt, part, query)
        }
        StaffPage::Export(which) => export::reply(app, store, *which),
    }
}
