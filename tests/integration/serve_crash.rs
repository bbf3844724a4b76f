//! `whitted serve` killed (SIGKILL) while an upload is half received, a project runs and
//! images are checked; started again on the same data: every accepted attempt is there,
//! finished or queued again and then finished, none twice; the half-received upload left
//! nothing. And a backup taken while it serves is a consistent database.

use std::io::Write;
use std::net::TcpStream;
use std::time::{Duration, Instant};

use crate::common::{s, whitted};
use crate::serve::{attempt_of, multipart, project_files, render, Service};

fn count(db: &rusqlite::Connection, sql: &str) -> i64 {
    db.query_row(sql, [], |r| r.get(0)).expect(sql)
}

#[test]
fn a_kill_mid_upload_and_mid_run_loses_nothing_and_doubles_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["1201", "1202", "1203"]);
    let (students, _) = service.links();
    let (a, b, c) = (&students[0].1, &students[1].1, &students[2].1);
    let files = project_files();
    let refs: Vec<(&str, &[u8])> = files
        .iter()
        .map(|(n, b)| (n.as_str(), b.as_slice()))
        .collect();
    let project = attempt_of(&service.upload(a, &service.csrf(a), &refs));
    let png = render(dir.path(), "1");
    let images = attempt_of(&service.upload(b, &service.csrf(b), &[("tick2.png", &png)]));

    // A third student's upload, cut off half way: headers and half the announced body.
    let (kind, body) = multipart(&service.csrf(c), &[("tick2.png", &png)]);
    let mut half = TcpStream::connect(("127.0.0.1", service.port)).expect("connect");
    let head = format!(
        "POST {c}/upload HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Type: {kind}\r\n\
         Content-Length: {}\r\n\r\n",
        service.port,
        body.len()
    );
    half.write_all(head.as_bytes()).expect("head");
    half.write_all(&body[..body.len() / 2]).expect("half");

    // Killed once the project runs in the sandbox.
    let started = Instant::now();
    loop {
        let status = service.get(&format!("{project}/status")).text();
        if status.contains("\"running\"") {
            break;
        }
        assert!(started.elapsed() < Duration::from_secs(60), "{status}");
        std::thread::sleep(Duration::from_millis(100));
    }
    std::thread::sleep(Duration::from_millis(1500));
    let data = service.data.clone();
    service.kill();
    drop(half);

    let service = Service::restart(dir.path());
    let project_done = service.wait_done(&project, Duration::from_secs(300));
    assert_eq!(project_done["passed"], true, "{project_done}");
    service.wait_done(&images, Duration::from_secs(120));
    let page = service.get(&project).text();
    assert!(
        page.contains("Run 2 times"),
        "the interrupted run ran again: {page}"
    );
    assert!(
        !service.get(c).text().contains("tick2.png"),
        "the half upload is no attempt"
    );

    // While it serves: a backup, which is a consistent database.
    let copy = dir.path().join("backup.sqlite");
    let backup = whitted(
        dir.path(),
        &["serve", "backup", s(&copy), "--data", s(&data)],
    );
    assert!(
        backup.status.success(),
        "{}",
        String::from_utf8_lossy(&backup.stderr)
    );
    use std::os::unix::fs::PermissionsExt;
    let mode = std::fs::metadata(&copy)
        .expect("the copy")
        .permissions()
        .mode();
    assert_eq!(
        mode & 0o777,
        0o600,
        "the copy holds the secrets: its user's alone"
    );
    let again = whitted(
        dir.path(),
        &["serve", "backup", s(&copy), "--data", s(&data)],
    );
    assert_eq!(
        again.status.code(),
        Some(2),
        "an existing file is not overwritten"
    );
    let db = rusqlite::Connection::open(&copy).expect("the copy opens");
    let check: String = db
        .query_row("PRAGMA integrity_check", [], |r| r.get(0))
        .expect("check");
    assert_eq!(check, "ok");
    assert_eq!(
        count(&db, "SELECT count(*) FROM attempts"),
        2,
        "every accepted attempt, once"
    );
    assert_eq!(
        count(&db, "SELECT count(*) FROM results"),
        2,
        "one result each"
    );
    assert_eq!(
        count(&db, "SELECT count(*) FROM attempts WHERE status <> 'done'"),
        0
    );
    assert_eq!(
        count(&db, "SELECT count(*) FROM attempts a JOIN students s ON s.number = a.student WHERE s.id = '1203'"),
        0
    );
    // On disk: an upload folder per attempt, nothing half received.
    let uploads = std::fs::read_dir(data.join("uploads"))
        .expect("uploads")
        .count();
    assert_eq!(uploads, 2);
    assert_eq!(
        std::fs::read_dir(data.join("incoming"))
            .expect("incoming")
            .count(),
        0
    );
    let journal: String = rusqlite::Connection::open(data.join("whitted-serve.sqlite"))
        .expect("db")
        .query_row("PRAGMA journal_mode", [], |r| r.get(0))
        .expect("mode");
    assert_eq!(journal, "wal");
}
