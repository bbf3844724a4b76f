//! `whitted serve` against hostile clients: the viewer's (oversized and stalled heads, a
//! foreign Host, every method, many connections) and the uploads' own (a 1 GB body, a zip
//! bomb, a PNG bomb, path traversal in file names, forged and missing CSRF tokens, a revoked
//! link, too many uploads). Each refusal says why; after each, the service still answers.

use std::io::Write;
use std::net::TcpStream;
use std::time::{Duration, Instant};

use crate::common::{root, s, whitted};
use crate::serve::{attempt_of, raw, render, Service};

/// The student page answers within two seconds.
fn answers(service: &Service, link: &str) -> bool {
    let started = Instant::now();
    service.get(link).status == 200 && started.elapsed() < Duration::from_secs(2)
}

fn zip_bomb() -> Vec<u8> {
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    out.start_file("src/Renderer.java", options).expect("entry");
    let zeros = vec![b' '; 1 << 20];
    for _ in 0..64 {
        out.write_all(&zeros).expect("write");
    }
    out.finish().expect("zip").into_inner()
}

#[test]
fn hostile_requests_are_refused_with_a_reason_and_the_service_goes_on() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["ab123", "cd456"]);
    let (students, _) = service.links();
    let (a, b) = (&students[0].1, &students[1].1);
    let csrf = service.csrf(a);
    let port = service.port;

    // The viewer's: a foreign Host (DNS rebinding), two Hosts, an absolute-form target, every
    // other method, a head past the limit, a body on a GET.
    let foreign = format!("GET {a} HTTP/1.1\r\nHost: evil.example\r\nConnection: close\r\n\r\n");
    assert_eq!(raw(port, foreign.as_bytes()).status, 403);
    let two = format!(
        "GET {a} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nHost: 127.0.0.1:{port}\r\n\
         Connection: close\r\n\r\n"
    );
    assert_eq!(raw(port, two.as_bytes()).status, 400);
    let absolute = format!("GET http://evil.example{a} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n");
    assert_eq!(raw(port, absolute.as_bytes()).status, 403);
    for method in ["PUT", "DELETE", "OPTIONS", "PATCH"] {
        assert_eq!(service.request(method, a, &[], b"").status, 405, "{method}");
    }
    let huge_head = format!(
        "GET {a} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Big: {}\r\n\r\n",
        "x".repeat(64 << 10)
    );
    assert!(matches!(raw(port, huge_head.as_bytes()).status, 0 | 431));
    assert_eq!(service.request("GET", a, &[], b"a body").status, 413);
    // A client that stalls mid-head holds one connection, not the service.
    let mut stalled = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    stalled
        .write_all(b"GET / HTTP/1.1\r\nHost: 127.0")
        .expect("partial");
    let idle: Vec<TcpStream> = (0..40)
        .filter_map(|_| TcpStream::connect(("127.0.0.1", port)).ok())
        .collect();
    assert!(
        answers(&service, a),
        "answers beside stalled and idle clients"
    );
    drop((stalled, idle));

    // A 1 GB body is refused from its announced length, before a byte of it is read.
    let started = Instant::now();
    let gigabyte = format!(
        "POST {a}/upload HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: multipart/form-data; \
         boundary=x\r\nContent-Length: 1073741824\r\nConnection: close\r\n\r\n--x\r\n"
    );
    let refused = raw(port, gigabyte.as_bytes());
    assert_eq!(refused.status, 413);
    assert!(refused.text().contains("too large"), "{}", refused.text());
    assert!(started.elapsed() < Duration::from_secs(5));

    // Forged, missing and stale CSRF tokens.
    let png = render(dir.path(), "2");
    let forged = service.upload(a, &"0".repeat(32), &[("tick2.png", &png)]);
    assert_eq!(forged.status, 403);
    assert!(forged.text().contains("forged"), "{}", forged.text());
    let (kind, body) = crate::serve::multipart(&csrf, &[("tick2.png", &png)]);
    let files_first = String::from_utf8_lossy(&body)
        .replacen(
            &format!("name=\"csrf\"\r\n\r\n{csrf}"),
            "name=\"csrf\"\r\n\r\n",
            1,
        )
        .into_bytes();
    let missing = service.request(
        "POST",
        &format!("{a}/upload"),
        &[("Content-Type", &kind)],
        &files_first,
    );
    assert_eq!(missing.status, 403);
    let cross = service.request(
        "POST",
        &format!("{a}/upload"),
        &[("Content-Type", &kind), ("Sec-Fetch-Site", "cross-site")],
        &body,
    );
    assert_eq!(cross.status, 403, "an upload from another site");

    // A zip bomb: 64 MiB of source in a small zip.
    let bomb = zip_bomb();
    assert!(bomb.len() < 1 << 20);
    let refused = service.upload(a, &csrf, &[("project.zip", &bomb)]);
    assert_eq!(refused.status, 422);
    assert!(
        refused.text().contains("expand to more than"),
        "{}",
        refused.text()
    );

    // A PNG bomb: 60000 x 60000 pixels declared in 69 bytes.
    let bomb = std::fs::read(root().join("tests/bad_images/png_huge.png")).expect("png");
    let refused = service.upload(a, &csrf, &[("tick2.png", &bomb)]);
    assert_eq!(refused.status, 422);
    assert!(
        refused.text().contains("60000 x 60000"),
        "{}",
        refused.text()
    );

    // Path traversal in file names: kept under whitted's own names, shown as the last part.
    let climbing = service.upload(a, &csrf, &[("../../../../tmp/escape.png", &png)]);
    let attempt = attempt_of(&climbing);
    assert!(!dir.path().join("escape.png").exists());
    let page = service.get(&attempt).text();
    assert!(
        page.contains("escape.png") && !page.contains("../"),
        "{page}"
    );
    let names: Vec<String> = walk(&service.data);
    assert!(names.iter().all(|n| !n.contains("escape")), "{names:?}");
    let java = service.upload(a, &csrf, &[("../../Evil$.java", b"class Evil {}")]);
    assert_eq!(java.status, 422);

    // Too many uploads in a minute: the 7th is refused with when to come back.
    let mut statuses = Vec::new();
    for _ in 0..6 {
        statuses.push(
            service
                .upload(b, &service.csrf(b), &[("tick2.png", &png)])
                .status,
        );
    }
    assert_eq!(statuses, [303; 6]);
    let limited = service.upload(b, &service.csrf(b), &[("tick2.png", &png)]);
    assert_eq!(limited.status, 429);
    assert!(
        limited.text().contains("at most 6 a minute"),
        "{}",
        limited.text()
    );

    // A revoked link: refused before its body is read, and says what to do.
    let revoke = whitted(
        dir.path(),
        &["serve", "revoke", "ab123", "--data", s(&service.data)],
    );
    assert!(revoke.status.success());
    let revoked = service.upload(a, &csrf, &[("tick2.png", &png)]);
    assert_eq!(revoked.status, 403);
    assert!(revoked.text().contains("revoked"), "{}", revoked.text());
    assert!(answers(&service, b), "still answers after all of it");
}

/// Every file name under `dir`.
fn walk(dir: &std::path::Path) -> Vec<String> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        out.push(entry.file_name().to_string_lossy().into_owned());
        if entry.path().is_dir() {
            out.extend(walk(&entry.path()));
        }
    }
    out
}
