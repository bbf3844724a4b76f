//! The viewer against hostile local clients: oversized, stalled and malformed requests, every
//! method, many connections, and layer names that need percent-encoding. After each, the
//! viewer must still answer a well-behaved request promptly.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;

use crate::view::Viewer;
use std::process::Command;
use std::time::{Duration, Instant};

/// The status of a raw request, or None when the server closed without answering.
fn raw(viewer: &Viewer, request: &[u8]) -> Option<u16> {
    let mut stream = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(20)))
        .expect("timeout");
    let _ = stream.write_all(request);
    let mut head = [0u8; 12];
    stream.read_exact(&mut head).ok()?;
    std::str::from_utf8(&head[9..12]).ok()?.parse().ok()
}

/// A well-behaved request, answered within two seconds.
fn answers(viewer: &Viewer) -> bool {
    let started = Instant::now();
    let request = format!(
        "GET /api/image?token={} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n\r\n",
        viewer.token(),
        viewer.port
    );
    let ok = raw(viewer, request.as_bytes()) == Some(200);
    ok && started.elapsed() < Duration::from_secs(2)
}

/// A 640x480 EXR whose only layer has a name that needs every kind of encoding.
fn odd_names(dir: &Path) -> std::path::PathBuf {
    use exr::prelude::*;
    let n = 640 * 480;
    // As UTF-8 bytes, as OpenEXR specifies (the crate's `From<&str>` would store Latin-1).
    let utf8 = |name: String| Text::from_slice_unchecked(name.as_bytes());
    let channels = ["R", "G", "B"].map(|c| {
        let name = utf8(format!("a b&=+#%/?é.{c}"));
        AnyChannel::new(name, FlatSamples::F32(vec![0.5; n]))
    });
    let beauty = ["R", "G", "B", "A"].map(|c| AnyChannel::new(c, FlatSamples::F32(vec![1.0; n])));
    let all: Vec<AnyChannel<FlatSamples>> = channels.into_iter().chain(beauty).collect();
    let layer = Layer::new(
        (640, 480),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(all.into()),
    );
    let path = dir.join("odd.exr");
    Image::from_layer(layer)
        .write()
        .to_file(&path)
        .expect("exr");
    path
}

#[test]
fn the_viewer_survives_hostile_clients() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = odd_names(dir.path());
    let mut viewer = Viewer::start(dir.path(), &exr);
    let host = format!("Host: 127.0.0.1:{}\r\n", viewer.port);
    assert!(answers(&viewer));

    // A body of 10^14 bytes announced, without a token: refused, nothing allocated.
    let huge = format!("POST / HTTP/1.1\r\n{host}Content-Length: 100000000000000\r\n\r\n");
    assert_eq!(raw(&viewer, huge.as_bytes()), Some(405));
    let huge = format!(
        "GET /?token={} HTTP/1.1\r\n{host}Content-Length: 100000000000000\r\n\r\n",
        viewer.token()
    );
    assert_eq!(raw(&viewer, huge.as_bytes()), Some(413));
    assert!(viewer.alive() && answers(&viewer), "after a huge body");

    // Every method.
    for (method, status) in [
        ("GET", 200),
        ("HEAD", 200),
        ("POST", 405),
        ("PUT", 405),
        ("DELETE", 405),
        ("OPTIONS", 405),
        ("PATCH", 405),
        ("TRACE", 405),
    ] {
        let request = format!(
            "{method} /?token={} HTTP/1.1\r\n{host}Connection: close\r\n\r\n",
            viewer.token()
        );
        assert_eq!(raw(&viewer, request.as_bytes()), Some(status), "{method}");
    }
    // Two Host headers; an oversized head.
    let two = format!(
        "GET /?token={} HTTP/1.1\r\n{host}{host}\r\n",
        viewer.token()
    );
    assert_eq!(raw(&viewer, two.as_bytes()), Some(400));
    let big = format!(
        "GET /?token={} HTTP/1.1\r\n{host}X-Junk: {}\r\n\r\n",
        viewer.token(),
        "x".repeat(100_000)
    );
    assert!(matches!(
        raw(&viewer, big.as_bytes()),
        Some(431) | Some(400) | None
    ));
    assert!(viewer.alive() && answers(&viewer), "after malformed heads");

    // A client that stalls half-way through its head, and one that never reads a layer.
    let mut stalled = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
    stalled.write_all(b"GET /?token=").expect("send");
    let mut reader = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
    let name = "a%20b%26%3D%2B%23%25%2F%3F%C3%A9";
    let layer = format!(
        "GET /api/layer?name={name}&token={} HTTP/1.1\r\n{host}\r\n",
        viewer.token()
    );
    reader.write_all(layer.as_bytes()).expect("send");
    assert!(answers(&viewer), "a stalled client held the server");

    // The encoded name is served: 640 * 480 pixels of 3 channels.
    let mut stream = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(20)))
        .expect("timeout");
    let request = format!(
        "GET /api/layer?name={name}&token={} HTTP/1.1\r\n{host}Connection: close\r\n\r\n",
        viewer.token()
    );
    stream.write_all(request.as_bytes()).expect("send");
    let mut reply = Vec::new();
    stream.read_to_end(&mut reply).expect("reply");
    assert!(
        reply.starts_with(b"HTTP/1.1 200"),
        "{}",
        String::from_utf8_lossy(&reply[..40.min(reply.len())])
    );
    assert!(reply.len() > 640 * 480 * 3 * 4);

    // Many connections at once, held open: the server stays up and answers again once they
    // are gone.
    let many: Vec<TcpStream> = (0..300)
        .filter_map(|_| TcpStream::connect(("127.0.0.1", viewer.port)).ok())
        .collect();
    assert!(viewer.alive());
    // One more, past the limit: answered 503 with Retry-After (a reset reads as a broken
    // site; a 503 is retried by a page's poller), not dropped.
    let mut past = TcpStream::connect(("127.0.0.1", viewer.port)).expect("connect");
    past.set_read_timeout(Some(Duration::from_secs(10)))
        .expect("timeout");
    past.write_all(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .expect("send");
    let mut busy = Vec::new();
    past.read_to_end(&mut busy).expect("busy reply");
    let busy = String::from_utf8_lossy(&busy);
    assert!(busy.starts_with("HTTP/1.1 503 "), "{busy}");
    assert!(busy.contains("Retry-After: 2"), "{busy}");
    assert!(busy.ends_with("try again in a moment.\r\n"), "{busy}");
    drop(many);
    drop((stalled, reader));
    std::thread::sleep(Duration::from_millis(300));
    assert!(viewer.alive() && answers(&viewer), "after many connections");
}

#[test]
fn utf8_channel_names_are_shown_and_selectable_everywhere() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = odd_names(d);
    let exr = exr.to_str().expect("utf-8");
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_whitted"))
            .args(args)
            .current_dir(d)
            .output()
            .expect("runs")
    };
    let info = run(&["info", exr, "--json"]);
    assert!(info.status.success());
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(text.contains("a b&=+#%/?é"), "{text}");
    assert!(!text.contains("Ã©"), "Latin-1 decoded: {text}");
    let tonemap = run(&["tonemap", exr, "--layer", "a b&=+#%/?é", "-o", "t.png"]);
    assert!(
        tonemap.status.success(),
        "{}",
        String::from_utf8_lossy(&tonemap.stderr)
    );
    let sheet = run(&["sheet", exr, "--layers", "a b&=+#%/?é", "-o", "s.png"]);
    assert!(
        sheet.status.success(),
        "{}",
        String::from_utf8_lossy(&sheet.stderr)
    );
    let diff = run(&["diff", exr, exr, "--layers", "a b&=+#%/?é"]);
    assert!(
        diff.status.success(),
        "{}",
        String::from_utf8_lossy(&diff.stderr)
    );
}

#[test]
fn a_student_png_opens_against_a_reference_png() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    for (name, bounces) in [("mine.png", "1"), ("reference.png", "2")] {
        let run = Command::new(env!("CARGO_BIN_EXE_whitted"))
            .args([
                "-q", "-o", name, "-b", bounces, "--width", "64", "--height", "48",
            ])
            .current_dir(d)
            .output()
            .expect("render");
        assert!(run.status.success());
    }
    let viewer = Viewer::start_with(d, &["mine.png", "--reference", "reference.png"]);
    let request = |path: &str| {
        let target = format!("{path}token={}", viewer.token());
        let request = format!(
            "GET {target} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n\r\n",
            viewer.port
        );
        raw(&viewer, request.as_bytes())
    };
    assert_eq!(request("/api/image?"), Some(200));
    assert_eq!(
        request("/api/layer?name=beauty&which=reference&"),
        Some(200)
    );
    // A reference of another size is refused before the server starts.
    let run = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(["-q", "-o", "small.png", "--width", "32", "--height", "24"])
        .current_dir(d)
        .output()
        .expect("render");
    assert!(run.status.success());
    let refused = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args([
            "view",
            "mine.png",
            "--reference",
            "small.png",
            "--no-browser",
        ])
        .current_dir(d)
        .output()
        .expect("view");
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("cannot be compared"));
}

#[test]
fn the_new_routes_need_the_token_check_their_parameters_and_never_kill_the_viewer() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = crate::view::small_render(d);
    let mut viewer = Viewer::start_with(
        d,
        &[
            exr.to_str().expect("utf-8"),
            "--reference",
            exr.to_str().expect("utf-8"),
            "--watch",
        ],
    );
    let host = format!("Host: 127.0.0.1:{}\r\n", viewer.port);
    let get = |target: &str| {
        let request = format!("GET {target} HTTP/1.1\r\n{host}Connection: close\r\n\r\n");
        raw(&viewer, request.as_bytes())
    };
    let routes = [
        "/api/version",
        "/api/check",
        "/api/stats?name=beauty",
        "/api/trees?x=1&y=1",
        "/api/layer?name=beauty&which=squared-error&tx=0&ty=0",
    ];
    for route in routes {
        assert_eq!(get(route), Some(403), "{route} without the token");
        let sep = if route.contains('?') { '&' } else { '?' };
        let wrong = format!(
            "GET {route}{sep}token={} HTTP/1.1\r\nHost: evil.example:{}\r\n\r\n",
            viewer.token(),
            viewer.port
        );
        assert_eq!(
            raw(&viewer, wrong.as_bytes()),
            Some(403),
            "{route}: rebinding"
        );
    }
    let token = viewer.token().to_string();
    for (target, status) in [
        ("/api/version", 200),
        ("/api/check", 404),
        ("/api/stats?name=beauty&which=relative-squared-error", 200),
        ("/api/stats?name=nothing", 404),
        ("/api/stats?name=beauty&which=%00", 400),
        ("/api/stats", 400),
        // tick2.xml is the embedded scene the EXR records: its trees are there.
        ("/api/trees?x=1&y=1", 200),
        ("/api/trees?x=160&y=0", 404),
        ("/api/trees?x=99999999999999999999&y=1", 400),
        ("/api/layer?name=beauty&which=error&tx=0&ty=0", 200),
        ("/api/layer?name=beauty&tx=18446744073709551615&ty=0", 404),
        ("/api/layer?name=beauty&tx=0&ty=0&step=65536", 200),
        ("/api/layer?name=beauty&tx=1&ty=0&step=65536", 404),
        ("/api/layer?name=beauty&tx=0", 400),
        ("/api/pixel?x=159&y=119", 200),
        ("/api/pixel?x=160&y=0", 404),
    ] {
        let sep = if target.contains('?') { '&' } else { '?' };
        assert_eq!(
            get(&format!("{target}{sep}token={token}")),
            Some(status),
            "{target}"
        );
    }
    assert!(viewer.alive() && answers(&viewer), "after the new routes");
}
