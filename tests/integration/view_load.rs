//! The viewer under load: cheap routes (the version the page polls, the probe) answer while
//! heavy ones (statistics over every pixel) queue, and clients that ask for large layers and
//! never read them cannot make the viewer hold their replies in memory (issue 33, items 6-7).

use std::io::Write;
use std::net::TcpStream;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::common::*;
use crate::view::{http, Viewer};

/// A 1920x1080 image and a different reference of it, open in a viewer.
fn full_hd_pair(d: &Path) -> Viewer {
    render(d, "a.png", (1920, 1080), "2");
    render(d, "b.png", (1920, 1080), "0");
    Viewer::start_with(d, &["a.png", "--reference", "b.png"])
}

/// tick2 at `size` and `bounces`, as the PNG `name` in `d`.
fn render(d: &Path, name: &str, (width, height): (u32, u32), bounces: &str) {
    let (width, height) = (width.to_string(), height.to_string());
    let args = [
        "render", "--width", &width, "--height", &height, "-b", bounces, "-o", name,
    ];
    let out = whitted(d, &args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn cheap_routes_do_not_queue_behind_heavy_ones() {
    let dir = tempfile::tempdir().expect("tempdir");
    let viewer = full_hd_pair(dir.path());
    let (port, token) = (viewer.port, viewer.token().to_string());
    // When each heavy reply arrived, in order.
    let heavy_done = Arc::new(Mutex::new(Vec::new()));
    let heavy: Vec<_> = (0..16)
        .map(|_| {
            let (token, done) = (token.clone(), heavy_done.clone());
            std::thread::spawn(move || {
                let path =
                    format!("/api/stats?name=beauty&which=relative-squared-error&token={token}");
                let (status, _) = http(port, "GET", &path, &format!("127.0.0.1:{port}"), None);
                assert_eq!(status, 200);
                done.lock().expect("lock").push(Instant::now());
            })
        })
        .collect();
    std::thread::sleep(Duration::from_millis(100));
    for cheap in [
        "/api/version",
        "/api/pixel?x=3&y=3",
        "/api/layer?name=beauty&tx=1&ty=1",
    ] {
        let (status, _) = viewer.get(cheap);
        assert_eq!(status, 200, "{cheap}");
        // Ordered, not timed: queued behind them (the bug) it comes after 13 of the 16.
        let finished = heavy_done.lock().expect("lock").len();
        assert!(
            finished <= 6,
            "{cheap} answered only after {finished} of 16 statistics"
        );
    }
    for h in heavy {
        h.join().expect("a heavy request");
    }
}

/// The viewer's resident memory in MiB.
fn resident_mib(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).expect("status");
    let kib: u64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmRSS");
    kib / 1024
}

#[test]
fn unread_replies_are_bounded() {
    let dir = tempfile::tempdir().expect("tempdir");
    let viewer = full_hd_pair(dir.path());
    let before = resident_mib(viewer.pid());
    // 60 clients ask for a whole 24 MiB metric layer each and never read a byte: 1.4 GiB if
    // every reply were computed and held.
    let stalled: Vec<TcpStream> = (0..60)
        .map(|_| {
            let mut stream = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
            let request = format!(
                "GET /api/layer?name=beauty&which=squared-error&token={} HTTP/1.1\r\n\
                 Host: 127.0.0.1:{}\r\n\r\n",
                viewer.token(),
                viewer.port
            );
            stream.write_all(request.as_bytes()).expect("send");
            stream
        })
        .collect();
    let started = Instant::now();
    let mut peak = 0;
    while started.elapsed() < Duration::from_secs(8) {
        peak = peak.max(resident_mib(viewer.pid()));
        std::thread::sleep(Duration::from_millis(100));
    }
    // The budget of unsent replies (256 MiB) and a few replies being computed.
    assert!(
        peak < before + 400,
        "unread replies hold {} MiB",
        peak - before
    );
    // The cheap routes still answer meanwhile.
    assert_eq!(viewer.get("/api/version").0, 200);
    // Once the stalled clients go, their replies' memory is free for the others.
    drop(stalled);
    std::thread::sleep(Duration::from_millis(500));
    let (status, body) = viewer.get("/api/layer?name=beauty&which=squared-error");
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    assert_eq!(body.len(), 1920 * 1080 * 3 * 4);
}

/// The `X-Whitted-Version` header of a GET of `path` (with the token).
fn version_header(viewer: &Viewer, path: &str) -> Option<u64> {
    let mut stream = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
    let sep = if path.contains('?') { '&' } else { '?' };
    let request = format!(
        "GET {path}{sep}token={} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n\r\n",
        viewer.token(),
        viewer.port
    );
    stream.write_all(request.as_bytes()).expect("send");
    let mut reply = Vec::new();
    std::io::Read::read_to_end(&mut stream, &mut reply).expect("receive");
    let head = String::from_utf8_lossy(&reply).to_ascii_lowercase();
    let head = head.split("\r\n\r\n").next().unwrap_or("").to_string();
    head.lines()
        .find_map(|l| l.strip_prefix("x-whitted-version:"))
        .and_then(|v| v.trim().parse().ok())
}

#[test]
fn replies_say_which_load_they_come_from() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    render(d, "a.png", (64, 48), "2");
    let viewer = Viewer::start_with(d, &["a.png", "--watch"]);
    let routes = [
        "/api/layer?name=beauty&tx=0&ty=0",
        "/api/layer?name=beauty&step=2",
        "/api/stats?name=beauty",
        "/api/pixel?x=1&y=1",
    ];
    for route in routes {
        assert_eq!(version_header(&viewer, route), Some(1), "{route}");
    }
    render(d, "new.png", (64, 48), "0");
    std::fs::rename(d.join("new.png"), d.join("a.png")).expect("replace");
    let started = Instant::now();
    while viewer.json("/api/version")["version"] == 1 {
        assert!(started.elapsed() < Duration::from_secs(60), "no reload");
        std::thread::sleep(Duration::from_millis(50));
    }
    for route in routes {
        assert_eq!(version_header(&viewer, route), Some(2), "{route}");
    }
}
