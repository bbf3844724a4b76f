//! `whitted serve` end to end over HTTP: a class of students, each reaching only their own
//! work by their link; images checked at once, projects run in the sandbox; the staff page
//! and its exports; and, in Chromium, a student who uploads and reads the result.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{s, whitted};

/// A running `whitted serve`, killed when dropped.
pub struct Service {
    child: Child,
    pub port: u16,
    pub data: PathBuf,
}

impl Service {
    /// Serves `course` from `dir/data` with the roster `ids` (one a line), `-j 1`.
    pub fn start(dir: &Path, ids: &[&str]) -> Service {
        Service::start_with(dir, ids, &[])
    }

    /// As `start`, with more options.
    pub fn start_with(dir: &Path, ids: &[&str], options: &[&str]) -> Service {
        let roster = dir.join("roster.txt");
        std::fs::write(&roster, ids.join("\n")).expect("roster");
        let mut args = vec!["--roster", s(&roster)];
        args.extend_from_slice(options);
        Service::run(dir, &args)
    }

    /// Starts it again on the same data (after a kill).
    pub fn restart(dir: &Path) -> Service {
        Service::run(dir, &[])
    }

    pub fn run(dir: &Path, extra: &[&str]) -> Service {
        Service::run_course(dir, "2016-17", extra)
    }

    /// As `run`, serving `course`.
    pub fn run_course(dir: &Path, course: &str, extra: &[&str]) -> Service {
        let data = dir.join("data");
        let mut child = Command::new(env!("CARGO_BIN_EXE_whitted"))
            .args([
                "serve",
                "--course",
                course,
                "--listen",
                "127.0.0.1:0",
                "--data",
            ])
            .arg(&data)
            .args(extra)
            .current_dir(dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("whitted serve starts");
        let mut first = String::new();
        BufReader::new(child.stdout.take().expect("stdout"))
            .read_line(&mut first)
            .expect("its first line");
        let port = first
            .split("http://127.0.0.1:")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|p| p.parse().ok())
            .unwrap_or_else(|| panic!("no port in {first:?}"));
        Service { child, port, data }
    }

    /// Every student's link path (`/s/...`) by id, and the staff's (`/staff/...`).
    pub fn links(&self) -> (Vec<(String, String)>, String) {
        let out = whitted(Path::new("."), &["serve", "links", "--data", s(&self.data)]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        let prefix = format!("http://127.0.0.1:{}", self.port);
        let mut students = Vec::new();
        let mut staff = String::new();
        for line in text.lines().skip(1) {
            let fields: Vec<&str> = line.split(',').collect();
            let path = fields[3].strip_prefix(&prefix).unwrap_or("").to_string();
            match fields[0] {
                "staff" => staff = path,
                id => students.push((id.to_string(), path)),
            }
        }
        (students, staff)
    }

    pub fn get(&self, path: &str) -> Reply {
        self.request("GET", path, &[], b"")
    }

    pub fn request(
        &self,
        method: &str,
        path: &str,
        headers: &[(&str, &str)],
        body: &[u8],
    ) -> Reply {
        let mut head = format!(
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n\
             Content-Length: {}\r\n",
            self.port,
            body.len()
        );
        for (name, value) in headers {
            head += &format!("{name}: {value}\r\n");
        }
        head += "\r\n";
        let mut bytes = head.into_bytes();
        bytes.extend_from_slice(body);
        raw(self.port, &bytes)
    }

    /// Uploads `files` (name, bytes) with `csrf` through `link`'s form.
    pub fn upload(&self, link: &str, csrf: &str, files: &[(&str, &[u8])]) -> Reply {
        self.upload_as(link, csrf, files, None)
    }

    /// As `upload`, each file with the scene `scene` chosen beside it (`tick2.xml:2`).
    pub fn upload_as(
        &self,
        link: &str,
        csrf: &str,
        files: &[(&str, &[u8])],
        scene: Option<&str>,
    ) -> Reply {
        let (content_type, body) = multipart_as(csrf, files, scene);
        self.request(
            "POST",
            &format!("{link}/upload"),
            &[("Content-Type", &content_type)],
            &body,
        )
    }

    /// The CSRF token of `link`'s form.
    pub fn csrf(&self, link: &str) -> String {
        let page = self.get(link).text();
        page.split("name=\"csrf\" value=\"")
            .nth(1)
            .and_then(|rest| rest.split('"').next())
            .expect("a CSRF token in the form")
            .to_string()
    }

    /// Waits until `attempt` (its page's path) is done; its status JSON.
    pub fn wait_done(&self, attempt: &str, within: Duration) -> serde_json::Value {
        self.watch_done(attempt, within).pop().expect("a status")
    }

    /// Every status JSON of `attempt` seen until it is done (polled every 100 ms), the last
    /// one done.
    pub fn watch_done(&self, attempt: &str, within: Duration) -> Vec<serde_json::Value> {
        let started = Instant::now();
        let mut seen = Vec::new();
        loop {
            let status = self.get(&format!("{attempt}/status"));
            assert_eq!(status.status, 200, "{}", status.text());
            let value: serde_json::Value = serde_json::from_slice(&status.body).expect("json");
            let done = value["status"] == "done";
            seen.push(value);
            if done {
                return seen;
            }
            assert!(
                started.elapsed() < within,
                "{attempt} not done: {:?}",
                seen.last()
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    pub fn kill(mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Service {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A reply: status, headers (lowercase names), body.
pub struct Reply {
    pub status: u16,
    pub head: String,
    pub body: Vec<u8>,
}

impl Reply {
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }

    pub fn header(&self, name: &str) -> Option<String> {
        let name = format!("{}:", name.to_ascii_lowercase());
        self.head.lines().find_map(|l| {
            l.to_ascii_lowercase()
                .starts_with(&name)
                .then(|| l[name.len()..].trim().to_string())
        })
    }
}

/// Sends `request` as it is; the reply (status 0 when the server closed without one).
pub fn raw(port: u16, request: &[u8]) -> Reply {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(120)))
        .expect("timeout");
    let _ = stream.write_all(request);
    let mut all = Vec::new();
    let _ = stream.read_to_end(&mut all);
    let text = String::from_utf8_lossy(&all);
    let Some((head, _)) = text.split_once("\r\n\r\n") else {
        return Reply {
            status: 0,
            head: String::new(),
            body: Vec::new(),
        };
    };
    let body = all[head.len() + 4..].to_vec();
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    Reply {
        status,
        head: head.to_string(),
        body,
    }
}

/// A multipart form of the page's fields: `csrf`, then each file as `files`.
pub fn multipart(csrf: &str, files: &[(&str, &[u8])]) -> (String, Vec<u8>) {
    multipart_as(csrf, files, None)
}

/// As `multipart`, with the select `scene` after each file, as the page's rows send it.
pub fn multipart_as(csrf: &str, files: &[(&str, &[u8])], scene: Option<&str>) -> (String, Vec<u8>) {
    let boundary = "----whittedTestBoundary7MA4YWxkTrZu0gW";
    let mut body =
        format!("--{boundary}\r\nContent-Disposition: form-data; name=\"csrf\"\r\n\r\n{csrf}\r\n")
            .into_bytes();
    for (name, bytes) in files {
        body.extend_from_slice(
            format!(
                "--{boundary}\r\nContent-Disposition: form-data; name=\"files\"; \
                 filename=\"{name}\"\r\nContent-Type: application/octet-stream\r\n\r\n"
            )
            .as_bytes(),
        );
        body.extend_from_slice(bytes);
        body.extend_from_slice(b"\r\n");
        if let Some(scene) = scene {
            body.extend_from_slice(
                format!(
                    "--{boundary}\r\nContent-Disposition: form-data; name=\"scene\"\r\n\r\n{scene}\r\n"
                )
                .as_bytes(),
            );
        }
    }
    body.extend_from_slice(format!("--{boundary}--\r\n").as_bytes());
    (format!("multipart/form-data; boundary={boundary}"), body)
}

/// The course's 2016-17 render at `bounces` (2 is right; 1 is the mistake bounces-minus-one).
pub fn render(dir: &Path, bounces: &str) -> Vec<u8> {
    let path = dir.join(format!("render-b{bounces}.png"));
    render_png(dir, &["--course", "2016-17", "-b", bounces], &path)
}

/// `whitted render ARGS -o PATH` in `dir`, which must succeed; the PNG it wrote.
pub fn render_png(dir: &Path, args: &[&str], path: &Path) -> Vec<u8> {
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", s(path)]);
    let out = whitted(dir, &all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read(path).expect("png")
}

/// The 2016-17 test submission's two files (the course's API, written for the tests).
pub fn project_files() -> Vec<(String, Vec<u8>)> {
    let dir = crate::common::root().join("tests/java/submission/gfx/tick2");
    ["Plane.java", "Renderer.java"]
        .iter()
        .map(|n| (n.to_string(), std::fs::read(dir.join(n)).expect("source")))
        .collect()
}

/// Whether the tests run as root.
fn is_root() -> bool {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("Uid:"))
                .map(|u| u.split_whitespace().next() == Some("0"))
        })
        .unwrap_or(false)
}

/// The attempt path a 303 after an upload points to.
pub fn attempt_of(reply: &Reply) -> String {
    assert_eq!(reply.status, 303, "{}", reply.text());
    reply.header("location").expect("a location")
}

#[test]
fn each_student_reaches_only_their_own_work_and_the_staff_see_everyone() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["1201", "1202"]);
    let (students, staff) = service.links();
    let (a, b) = (&students[0].1, &students[1].1);
    let mode = std::os::unix::fs::PermissionsExt::mode(
        &std::fs::metadata(&service.data)
            .expect("data")
            .permissions(),
    );
    assert_eq!(mode & 0o777, 0o700, "the data folder is private");

    let wrong = render(dir.path(), "1");
    let attempt = attempt_of(&service.upload_as(
        a,
        &service.csrf(a),
        &[("tick2.png", &wrong)],
        Some("tick2.xml:2"),
    ));
    assert!(attempt.starts_with(&format!("{a}/attempt/")), "{attempt}");
    let done = service.wait_done(&attempt, Duration::from_secs(120));
    assert_eq!(done["passed"], false);
    let page = service.get(&attempt);
    assert_eq!(page.status, 200);
    let text = page.text();
    assert!(
        text.contains("bounces-minus-one"),
        "the finding names the mistake: {text}"
    );
    assert!(text.contains("fix:"), "and says how to fix it");
    let csp = page.header("content-security-policy").expect("a CSP");
    assert!(
        csp.contains("script-src 'self'") && !csp.contains("unsafe-inline"),
        "{csp}"
    );
    assert!(!text.contains("<script>"), "no inline script");
    let report = service.get(&format!("{attempt}/report?n=0"));
    assert_eq!(report.status, 200);
    assert!(
        report.text().contains("data:image/png"),
        "the report shows the images"
    );
    let report_csp = report.header("content-security-policy").expect("csp");
    assert!(report_csp.starts_with("default-src 'none'") && !report_csp.contains("script"));
    assert!(
        service.get(a).text().contains("bounces-minus-one"),
        "listed on the student's page"
    );

    // Every route of A's attempt, through B's link: as if it did not exist.
    let number = attempt.rsplit('/').next().expect("number");
    for suffix in ["", "/status", "/report?n=0"] {
        let reply = service.get(&format!("{b}/attempt/{number}{suffix}"));
        assert_eq!(reply.status, 404, "{b}/attempt/{number}{suffix}");
        assert!(!reply.text().contains("bounces-minus-one"));
    }
    assert!(
        !service.get(b).text().contains("bounces-minus-one"),
        "B's page lists nothing of A"
    );
    // A's secret with B's number, and B's number with a made-up secret.
    let a_secret = a.rsplit('-').next().expect("secret");
    let b_number = b
        .trim_start_matches("/s/")
        .split('-')
        .next()
        .expect("number");
    for link in [
        format!("/s/{b_number}-{a_secret}"),
        format!("/s/{b_number}-{}", "0".repeat(32)),
    ] {
        assert_eq!(service.get(&link).status, 403, "{link}");
        assert_eq!(service.get(&format!("{link}/attempt/{number}")).status, 403);
    }
    // B cannot upload with A's form token.
    let forged = service.upload(b, &service.csrf(a), &[("tick2.png", &wrong)]);
    assert_eq!(forged.status, 403, "{}", forged.text());

    // The staff see both students, A's mistake ranked, B not started, and A's history.
    let class = service.get(&staff).text();
    assert!(class.contains("1201") && class.contains("1202"));
    assert!(class.contains("bounces-minus-one"));
    let not_started = class.split("Not started").nth(1).expect("the list");
    assert!(not_started.contains("1202") && !not_started.contains("1201"));
    assert_eq!(
        service.get(&format!("{staff}/attempt/{number}")).status,
        200
    );
    assert_eq!(
        service
            .get("/staff/0123456789abcdef0123456789abcdef")
            .status,
        403
    );
    assert_eq!(
        service.get("/staff/proxy").status,
        403,
        "no proxy is trusted"
    );

    // A revoked link answers no more, with what to do; reissued, the new one does.
    let revoke = whitted(
        dir.path(),
        &["serve", "revoke", "1201", "--data", s(&service.data)],
    );
    assert!(revoke.status.success());
    let refused = service.get(a);
    assert_eq!(refused.status, 403);
    assert!(refused.text().contains("revoked"), "{}", refused.text());
    let reissue = whitted(
        dir.path(),
        &["serve", "reissue", "1201", "--data", s(&service.data)],
    );
    assert!(reissue.status.success());
    let (again, _) = service.links();
    assert_ne!(&again[0].1, a);
    assert_eq!(service.get(&again[0].1).status, 200);
    assert_eq!(
        service
            .get(&format!("{}/attempt/{number}", again[0].1))
            .status,
        200
    );
}

#[test]
fn a_project_runs_in_the_sandbox_and_the_staff_export_it_as_grade_writes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["1201"]);
    let (students, staff) = service.links();
    let a = &students[0].1;
    let files = project_files();
    let as_refs: Vec<(&str, &[u8])> = files
        .iter()
        .map(|(n, b)| (n.as_str(), b.as_slice()))
        .collect();
    let attempt = attempt_of(&service.upload(a, &service.csrf(a), &as_refs));
    let first = service.get(&format!("{attempt}/status")).text();
    assert!(
        first.contains("\"queued\"") || first.contains("\"running\""),
        "{first}"
    );
    // A second project while the first waits is refused with the reason.
    let second = service.upload(a, &service.csrf(a), &as_refs);
    assert_eq!(second.status, 429, "{}", second.text());
    assert!(second.text().contains("still queued or running"));
    let seen = service.watch_done(&attempt, Duration::from_secs(300));
    let done = seen.last().expect("done");
    assert_eq!(done["passed"], true, "{done}");
    // While it ran, the status named the case running, k of n, from the year's suite.
    let suite: Vec<String> =
        whitted_check::check::suite::cases_of(whitted_core::course::Course::Y2016)
            .iter()
            .map(|c| c.name())
            .collect();
    let running: Vec<&serde_json::Value> = seen
        .iter()
        .filter(|v| v["step"]["step"] == "running")
        .collect();
    assert!(!running.is_empty(), "no running case seen: {seen:?}");
    for v in &running {
        let step = &v["step"];
        let case = step["case"].as_str().expect("a case name");
        assert!(
            suite.iter().any(|c| c == case),
            "{case} is not a case of {suite:?}"
        );
        let (k, n) = (step["index"].as_u64(), step["of"].as_u64());
        assert_eq!(n, Some(suite.len() as u64), "{step}");
        assert!(
            k.is_some_and(|k| (1..=suite.len() as u64).contains(&k)),
            "{step}"
        );
    }
    // Its CPU time: every process its run started, sandboxed JVMs included (at least the
    // JVMs' start, 7 of them), where a counting cgroup can be made (as root on cgroup v1).
    let countable = Path::new("/sys/fs/cgroup/cpuacct").is_dir() && is_root();
    match done["cpu_seconds"].as_f64() {
        Some(cpu) => assert!(cpu > 1.0 && cpu < 600.0, "{done}"),
        None => assert!(!countable, "not measured although it can be: {done}"),
    }
    let page = service.get(&attempt).text();
    assert!(page.contains("5 of 5 cases pass"));
    // Its progress in the handout's order, as check prints it, not alphabetically.
    let at = |stage: &str| page.find(&format!("{stage} done")).expect(stage);
    assert!(
        at("planes") < at("lights")
            && at("lights") < at("shadows")
            && at("shadows") < at("reflection"),
        "{page}"
    );
    if countable {
        assert!(page.contains("s of CPU"), "{page}");
        let class = service.get(&staff).text();
        assert!(class.contains("own CPU time"), "{class}");
    }
    let worksheet = service.get(&format!("{staff}/export/moodle.csv"));
    assert_eq!(worksheet.status, 200);
    let text = worksheet.text();
    assert!(
        text.starts_with("Identifier,Full name,Status,Grade"),
        "{text}"
    );
    assert!(
        text.contains("Participant 1201,") && text.contains(",graded,100,"),
        "{text}"
    );
    let class = service.get(&format!("{staff}/export/class.csv")).text();
    assert!(
        class.lines().nth(1).is_some_and(|l| l.starts_with("1201,")),
        "{class}"
    );
    let zip = service.get(&format!("{staff}/export/feedback.zip"));
    assert_eq!(
        zip.header("content-disposition").as_deref(),
        Some("attachment; filename=\"feedback.zip\"")
    );
    let archive = zip::ZipArchive::new(std::io::Cursor::new(zip.body)).expect("a zip");
    assert!(archive.file_names().any(|n| n.ends_with("report.html")));
}

/// Evaluates `expression` in the browser's page, None while the page is being replaced.
fn page_value(browser: &crate::view::Browser, expression: &str) -> Option<serde_json::Value> {
    let found = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        browser.script(&format!("return {expression}"), serde_json::json!([]))
    }));
    found.ok()
}

/// Waits (up to `seconds`) until `expression` is true in the page, whatever reloads meanwhile.
fn wait_page(browser: &crate::view::Browser, expression: &str, seconds: u64) {
    let started = Instant::now();
    while page_value(browser, expression) != Some(serde_json::json!(true)) {
        assert!(
            started.elapsed() < Duration::from_secs(seconds),
            "never true: {expression}"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// Chooses `paths` in the page's file input and presses Check.
fn choose_and_submit(browser: &crate::view::Browser, paths: &[PathBuf], scene: Option<&str>) {
    let input = browser.session(
        "POST",
        "/element",
        Some(serde_json::json!({"using": "css selector", "value": "input[type=file]"})),
    );
    let id = input["element-6066-11e4-a52e-4f735466cecf"]
        .as_str()
        .expect("the file input")
        .to_string();
    let text: Vec<&str> = paths.iter().map(|p| s(p)).collect();
    browser.session(
        "POST",
        &format!("/element/{id}/value"),
        Some(serde_json::json!({"text": text.join("\n")})),
    );
    if let Some(scene) = scene {
        browser.script(
            "document.querySelector('select[name=scene]').value = arguments[0]",
            serde_json::json!([scene]),
        );
    }
    browser.script(
        "document.querySelector('form button').click()",
        serde_json::json!([]),
    );
}

#[test]
fn in_chromium_a_student_uploads_and_reads_the_result_and_the_staff_see_the_class() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["1201", "1202"]);
    let (students, staff) = service.links();
    let origin = format!("http://127.0.0.1:{}", service.port);
    let (a, b) = (&students[0].1, &students[1].1);
    let browser = crate::view::Browser::start();

    // An image: checked at once; the page follows it and shows the finding and the report.
    render(dir.path(), "1");
    browser.navigate(&format!("{origin}{a}"));
    wait_page(&browser, "!!document.querySelector('input[type=file]')", 30);
    choose_and_submit(
        &browser,
        &[dir.path().join("render-b1.png")],
        Some("tick2.xml:2"),
    );
    wait_page(&browser, "!!document.querySelector('iframe')", 120);
    let text = page_value(&browser, "document.body.innerText").expect("text");
    let text = text.as_str().expect("a string");
    assert!(
        text.contains("bounces-minus-one") && text.contains("fix:"),
        "{text}"
    );
    let image_attempt = page_value(&browser, "location.pathname").expect("path");
    let image_attempt = image_attempt.as_str().expect("path").to_string();
    // The report in its frame shows the student's picture beside the expected one.
    wait_page(
        &browser,
        "(() => { const d = document.querySelector('iframe').contentDocument; \
         return !!d && d.querySelectorAll('img').length >= 2 })()",
        30,
    );
    browser.script(
        "const f = document.querySelector('iframe'); f.scrollIntoView(); \
         const img = f.contentDocument.querySelector('img'); \
         f.contentWindow.scrollTo(0, img.getBoundingClientRect().top + \
         f.contentWindow.scrollY - 60)",
        serde_json::json!([]),
    );
    browser.screenshot("serve_student.png");

    // A project: queued or running shown live, without a reload, then the result.
    let sources = dir.path().join("src");
    std::fs::create_dir_all(&sources).expect("src");
    let mut paths = Vec::new();
    for (name, bytes) in project_files() {
        std::fs::write(sources.join(&name), bytes).expect("source");
        paths.push(sources.join(&name));
    }
    browser.navigate(&format!("{origin}{a}"));
    wait_page(&browser, "!!document.querySelector('input[type=file]')", 30);
    choose_and_submit(&browser, &paths, None);
    wait_page(
        &browser,
        "(() => { const s = document.getElementById('state'); \
         return !!s && /Queued|Running/.test(s.textContent) })()",
        60,
    );
    // The case running, named live with its place in the suite, without a reload.
    wait_page(
        &browser,
        "(() => { const s = document.getElementById('state'); \
         return !!s && /Running: (running|checking) case [1-7] of 7: \\S+\\.xml -b \\d/.test(s.textContent) })()",
        120,
    );
    wait_page(
        &browser,
        "document.body.innerText.includes('5 of 5 cases pass')",
        300,
    );
    browser.navigate(&format!("{origin}{a}"));
    wait_page(
        &browser,
        "document.querySelectorAll('table tr').length === 3",
        30,
    );

    // The second student cannot open the first's attempt by its URL.
    let number = image_attempt.rsplit('/').next().expect("number");
    browser.navigate(&format!("{origin}{b}/attempt/{number}"));
    wait_page(&browser, "document.readyState === 'complete'", 30);
    let text = page_value(&browser, "document.body.innerText").expect("text");
    assert!(
        text.as_str()
            .is_some_and(|t| t.contains("not found") && !t.contains("bounces")),
        "{text}"
    );

    // The staff see both students: the first's mistake, the second not started.
    browser.navigate(&format!("{origin}{staff}"));
    wait_page(&browser, "document.readyState === 'complete'", 30);
    let text = page_value(&browser, "document.body.innerText").expect("text");
    let text = text.as_str().expect("text");
    assert!(text.contains("1201") && text.contains("1202"), "{text}");
    assert!(
        text.contains("bounces-minus-one") && text.contains("Not started"),
        "{text}"
    );
    browser.screenshot("serve_staff.png");
}

#[test]
fn the_user_header_opens_the_staff_page_only_from_the_trusted_proxy_for_the_staff() {
    let trusting = |proxy: &str| {
        let dir = tempfile::tempdir().expect("tempdir");
        let options = [
            "--trust-user-header",
            "X-Remote-User",
            "--trusted-proxy",
            proxy,
            "--staff",
            "boss,deputy",
        ];
        let service = Service::start_with(dir.path(), &["1201"], &options);
        let as_user = |user: Option<&str>| {
            let headers: Vec<(&str, &str)> =
                user.map(|u| ("X-Remote-User", u)).into_iter().collect();
            service.request("GET", "/staff/proxy", &headers, b"").status
        };
        let statuses = [
            as_user(Some("boss")),
            as_user(Some("deputy")),
            as_user(Some("1201")),
            as_user(None),
        ];
        (statuses, dir)
    };
    assert_eq!(trusting("127.0.0.1").0, [200, 200, 403, 403]);
    // The same header from an address that is not the proxy's is not believed.
    assert_eq!(trusting("192.0.2.1").0, [403, 403, 403, 403]);
    let dir = tempfile::tempdir().expect("tempdir");
    let alone = whitted(
        dir.path(),
        &[
            "serve",
            "--trust-user-header",
            "X-Remote-User",
            "--data",
            "d",
        ],
    );
    assert_eq!(
        alone.status.code(),
        Some(2),
        "the header needs the proxy's address"
    );
}

/// The course's 2016-17 render of its specular_test.xml: another scene than tick2.xml.
fn render_specular(dir: &Path) -> Vec<u8> {
    let path = dir.join("specular.png");
    let scene = crate::common::root().join("crates/check/scenes/check/specular_test.xml");
    render_png(dir, &["--course", "2016-17", "-i", s(&scene)], &path)
}

#[test]
fn each_image_is_checked_as_the_scene_it_is_and_another_scene_files_no_finding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["1201", "1202"]);
    let (students, staff) = service.links();
    let a = &students[0].1;
    let page = service.get(a).text();
    for choice in [
        "recognise it",
        "tick2.xml at 0 bounces",
        "specular_test.xml at 2 bounces",
    ] {
        assert!(page.contains(choice), "the form offers {choice}: {page}");
    }

    // A correct render at 0 bounces, left to be recognised: it passes as what it is.
    let b0 = render(dir.path(), "0");
    let recognised = attempt_of(&service.upload(a, &service.csrf(a), &[("b0.png", &b0)]));
    assert_eq!(
        service.wait_done(&recognised, Duration::from_secs(300))["passed"],
        true
    );
    // The same render said to be another scene: told so, with no mistake filed.
    let specular = render_specular(dir.path());
    let mislabelled = attempt_of(&service.upload_as(
        a,
        &service.csrf(a),
        &[("specular.png", &specular)],
        Some("tick2.xml:2"),
    ));
    assert_eq!(
        service.wait_done(&mislabelled, Duration::from_secs(300))["passed"],
        false
    );
    let text = service.get(&mislabelled).text();
    assert!(
        text.contains("this image is not tick2.xml at 2 bounces: choose its scene"),
        "{text}"
    );
    let class = service.get(&staff).text();
    assert!(
        class.contains("None diagnosed yet."),
        "no mistake ranked: {class}"
    );
    // A scene no year has is refused at the door.
    let refused = service.upload_as(a, &service.csrf(a), &[("x.png", &b0)], Some("../x:9"));
    assert_eq!(refused.status, 422);
    assert!(
        refused.text().contains("choose each image"),
        "{}",
        refused.text()
    );
}

#[test]
fn a_participants_export_keeps_its_names_and_no_worksheet_is_made_up() {
    let dir = tempfile::tempdir().expect("tempdir");
    let roster = dir.path().join("participants.csv");
    std::fs::write(
        &roster,
        "First name,Last name,ID number,Email address\nCarol,Davis,cd456,cd456@example.ac.uk\n",
    )
    .expect("roster");
    let service = Service::run(dir.path(), &["--roster", s(&roster)]);
    let (students, staff) = service.links();
    let a = &students[0].1;
    let files = project_files();
    let refs: Vec<(&str, &[u8])> = files
        .iter()
        .map(|(n, b)| (n.as_str(), b.as_slice()))
        .collect();
    let attempt = attempt_of(&service.upload(a, &service.csrf(a), &refs));
    assert_eq!(
        service.wait_done(&attempt, Duration::from_secs(300))["passed"],
        true
    );
    let page = service.get(&staff).text();
    assert!(page.contains("only the grading worksheet"), "{page}");
    let worksheet = service.get(&format!("{staff}/export/moodle.csv"));
    assert_eq!(worksheet.status, 409);
    assert!(
        worksheet.text().contains("not Moodle participant numbers"),
        "{}",
        worksheet.text()
    );
    assert!(!worksheet.text().contains("Participant cd456"));
    let class = service.get(&format!("{staff}/export/class.csv")).text();
    assert!(
        class
            .lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("cd456,Carol Davis,")),
        "{class}"
    );
    let zip = service.get(&format!("{staff}/export/feedback.zip"));
    let archive = zip::ZipArchive::new(std::io::Cursor::new(zip.body)).expect("a zip");
    let names: Vec<&str> = archive.file_names().collect();
    assert!(
        names
            .iter()
            .any(|n| n.starts_with("Carol Davis_cd456_assignsubmission_file_/")),
        "{names:?}"
    );
}

#[test]
fn each_image_of_an_attempt_is_shown_and_attempts_are_numbered_per_student() {
    let dir = tempfile::tempdir().expect("tempdir");
    let service = Service::start(dir.path(), &["1201", "1202"]);
    let (students, staff) = service.links();
    let (a, b) = (&students[0].1, &students[1].1);
    let (right, wrong) = (render(dir.path(), "2"), render(dir.path(), "1"));
    let tick2 = Some("tick2.xml:2");
    let first = attempt_of(&service.upload_as(a, &service.csrf(a), &[("a.png", &right)], tick2));
    service.wait_done(&first, Duration::from_secs(120));
    let one = attempt_of(&service.upload_as(b, &service.csrf(b), &[("b.png", &right)], tick2));
    service.wait_done(&one, Duration::from_secs(120));
    let three = attempt_of(&service.upload_as(
        b,
        &service.csrf(b),
        &[
            ("good.png", &right),
            ("wrong.png", &wrong),
            ("again.png", &right),
        ],
        tick2,
    ));
    assert_eq!(
        service.wait_done(&three, Duration::from_secs(300))["passed"],
        false
    );
    let page = service.get(&three).text();
    assert!(
        page.contains("<title>Attempt 2</title>"),
        "b's second: {page}"
    );
    assert!(page.contains("Attempt 2: images"), "{page}");
    assert!(
        page.contains("2 of 3 images pass (good.png, again.png); not wrong.png"),
        "{page}"
    );
    for name in [
        "good.png: identical",
        "wrong.png: differs",
        "again.png: identical",
    ] {
        assert!(page.contains(name), "each image's own text: {name}: {page}");
    }
    assert!(page.contains("bounces-minus-one"), "{page}");
    assert!(
        !page.contains("--verbose") && !page.contains("FILE.html"),
        "no command-line hints on the web: {page}"
    );
    let mine = service.get(b).text();
    assert!(
        mine.contains(&format!("{three}\">2</a>")) && mine.contains(&format!("{one}\">1</a>")),
        "{mine}"
    );
    let class = service.get(&staff).text();
    assert!(class.contains("Everyone has started."), "{class}");
    assert!(
        class.contains("<td>bounces-minus-one: one bounce fewer than --bounces</td>"),
        "the finding, not the heading: {class}"
    );
    assert!(!class.contains("(embedded), 640x480"), "{class}");
}

#[test]
fn a_wrong_roster_leaves_nothing_behind_and_revoke_says_what_it_did() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = whitted(
        dir.path(),
        &[
            "serve",
            "--course",
            "2016-17",
            "--listen",
            "127.0.0.1:0",
            "--roster",
            "missing.csv",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("missing.csv") && stderr.lines().count() == 1,
        "{stderr}"
    );
    assert!(
        !dir.path().join("whitted-serve").exists(),
        "no data folder made"
    );

    let service = Service::start(dir.path(), &["1201"]);
    let out = whitted(
        dir.path(),
        &["serve", "revoke", "1201", "--data", s(&service.data)],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(said.starts_with("revoked 1201's link"), "{said}");
    assert!(said.contains("whitted serve reissue --data"), "{said}");
    let (students, _) = service.links();
    assert_eq!(students[0].1, "", "the link is gone: {students:?}");
}

#[test]
fn a_tick1_star_screenshot_is_judged_as_check_star_judges_it_when_the_student_says_so() {
    let dir = tempfile::tempdir().expect("tempdir");
    let roster = dir.path().join("roster.txt");
    std::fs::write(&roster, "1201\n").expect("roster");
    let service = Service::run_course(dir.path(), "2020-21", &["--roster", s(&roster)]);
    let (students, _) = service.links();
    let a = &students[0].1;
    let page = service.get(a).text();
    assert!(page.contains("bump.xml (Tick 1*)"), "{page}");
    let path = dir.path().join("bump.png");
    let scene = crate::common::root().join("scenes/courses/tick1star/bump.xml");
    let png = render_png(dir.path(), &["--course", "2020-21", "-i", s(&scene)], &path);
    let value = page
        .split("value=\"")
        .map(|v| v.split('"').next().unwrap_or(""))
        .find(|v| v.starts_with("bump.xml:"))
        .expect("the bump choice")
        .to_string();
    let attempt =
        attempt_of(&service.upload_as(a, &service.csrf(a), &[("bump.png", &png)], Some(&value)));
    let done = service.wait_done(&attempt, Duration::from_secs(300));
    let text = service.get(&attempt).text();
    assert_eq!(done["passed"], true, "{text}");
    assert!(text.contains("bump.png: bump-correct"), "{text}");
    assert!(text.contains("option 1, bump mapping"), "{text}");
}
