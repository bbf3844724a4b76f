//! `whitted view`: the HTTP rules (loopback Host, token, nothing but the images), and the page
//! in a real headless Chromium driven over WebDriver (Debian's `chromium` and
//! `chromium-driver`, which `tools/test` installs): the probe reads the EXR's values, and
//! relighting in the page gives `whitted relight`'s PNG to within 1 LSB; TIFF, HDR and JPEG
//! open with their own values.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use crate::common::*;

/// A running `whitted view`, stopped (SIGTERM) when dropped.
pub struct Viewer {
    child: Child,
    url: String,
    pub port: u16,
}

impl Viewer {
    pub fn start(dir: &Path, exr: &Path) -> Viewer {
        Viewer::start_with(dir, &[exr.to_str().expect("utf-8")])
    }

    pub fn start_with(dir: &Path, args: &[&str]) -> Viewer {
        let mut all = vec!["view"];
        all.extend_from_slice(args);
        Viewer::run(dir, &all)
    }

    /// `whitted check ARGS --view --no-browser`.
    pub fn check(dir: &Path, args: &[&str]) -> Viewer {
        let mut all = vec!["check"];
        all.extend_from_slice(args);
        all.push("--view");
        Viewer::run(dir, &all)
    }

    /// Runs `whitted ARGS --no-browser` and reads the URL, which must be the first line.
    fn run(dir: &Path, args: &[&str]) -> Viewer {
        let mut child = Command::new(env!("CARGO_BIN_EXE_whitted"))
            .args(args)
            .arg("--no-browser")
            .current_dir(dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("whitted view starts");
        let mut line = String::new();
        BufReader::new(child.stdout.take().expect("stdout"))
            .read_line(&mut line)
            .expect("the URL line");
        let url = line.trim().to_string();
        assert!(url.starts_with("http://127.0.0.1:"), "{url}");
        let port = url["http://127.0.0.1:".len()..]
            .split('/')
            .next()
            .and_then(|p| p.parse().ok())
            .expect("a port");
        Viewer { child, url, port }
    }

    /// Sends SIGINT (Ctrl-C) and returns the exit status.
    fn interrupt(&mut self) -> Option<i32> {
        Command::new("kill")
            .args(["-INT", &self.child.id().to_string()])
            .status()
            .expect("kill");
        self.child.wait().expect("wait").code()
    }

    pub fn url(&self) -> &str {
        &self.url
    }

    /// GET `path` (with the token) from the viewer: (status, body).
    pub fn get(&self, path: &str) -> (u16, Vec<u8>) {
        let sep = if path.contains('?') { '&' } else { '?' };
        let host = format!("127.0.0.1:{}", self.port);
        http(
            self.port,
            "GET",
            &format!("{path}{sep}token={}", self.token()),
            &host,
            None,
        )
    }

    /// GET `path` as JSON, asserting 200.
    pub fn json(&self, path: &str) -> Value {
        let (status, body) = self.get(path);
        assert_eq!(status, 200, "{path}: {}", String::from_utf8_lossy(&body));
        serde_json::from_slice(&body).expect("json")
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    pub fn token(&self) -> &str {
        self.url.rsplit_once("token=").expect("a token").1
    }

    /// Whether the process is still running.
    pub fn alive(&mut self) -> bool {
        self.child.try_wait().expect("wait").is_none()
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        // A viewer a test already stopped is not signalled again (its pid may be reused).
        if let Ok(None) = self.child.try_wait() {
            let _ = Command::new("kill")
                .arg(self.child.id().to_string())
                .status();
        }
        let _ = self.child.wait();
    }
}

/// One HTTP/1.1 exchange: (status, body).
pub fn http(
    port: u16,
    method: &str,
    path: &str,
    host: &str,
    body: Option<&Value>,
) -> (u16, Vec<u8>) {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(60)))
        .expect("timeout");
    let payload = body.map(Value::to_string).unwrap_or_default();
    let request = format!(
        "{method} {path} HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n{payload}",
        payload.len()
    );
    stream.write_all(request.as_bytes()).expect("send");
    // Read the headers, then exactly the body they announce: a server may keep the
    // connection open whatever the request asked.
    let mut reader = BufReader::new(stream);
    let mut head = String::new();
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).expect("receive") == 0 || line == "\r\n" {
            break;
        }
        head.push_str(&line);
    }
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .expect("status");
    let lower = head.to_ascii_lowercase();
    let length = lower
        .lines()
        .find_map(|l| l.strip_prefix("content-length:"))
        .and_then(|n| n.trim().parse::<usize>().ok());
    let mut body = Vec::new();
    match length {
        Some(n) => {
            body.resize(n, 0);
            reader.read_exact(&mut body).expect("body");
        }
        None if lower.contains("transfer-encoding: chunked") => loop {
            let mut size = String::new();
            reader.read_line(&mut size).expect("chunk size");
            let n = usize::from_str_radix(size.trim(), 16).expect("hex size");
            let mut chunk = vec![0; n + 2];
            reader.read_exact(&mut chunk).expect("chunk");
            if n == 0 {
                break;
            }
            body.extend_from_slice(&chunk[..n]);
        },
        None => {
            reader.read_to_end(&mut body).expect("body");
        }
    }
    (status, body)
}

pub fn small_render(dir: &Path) -> PathBuf {
    render_exr(
        dir,
        &scene("tick2.xml"),
        "view.exr",
        &["--width", "160", "--height", "120"],
    )
}

#[test]
fn the_viewer_serves_only_its_images_to_loopback_with_the_token() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = small_render(dir.path());
    let viewer = Viewer::start(dir.path(), &exr);
    let host = format!("127.0.0.1:{}", viewer.port);
    let token = viewer.token().to_string();
    let get = |path: &str, host: &str| http(viewer.port, "GET", path, host, None);
    assert_eq!(get(&format!("/?token={token}"), &host).0, 200);
    assert_eq!(get("/", &host).0, 403, "no token");
    assert_eq!(get("/?token=0123", &host).0, 403, "wrong token");
    assert_eq!(
        get(&format!("/?token={token}"), "evil.example:80").0,
        403,
        "rebinding"
    );
    assert_eq!(
        get(
            &format!("/?token={token}"),
            &format!("localhost:{}", viewer.port)
        )
        .0,
        200
    );
    for path in [
        "/../../etc/passwd",
        "/view.exr",
        "/api/layer?name=../../etc/passwd",
    ] {
        let sep = if path.contains('?') { '&' } else { '?' };
        assert_eq!(
            get(&format!("{path}{sep}token={token}"), &host).0,
            404,
            "{path}"
        );
    }
    let (status, body) = get(&format!("/api/image?token={token}"), &host);
    assert_eq!(status, 200);
    let meta: Value = serde_json::from_slice(&body).expect("json");
    assert_eq!(
        (meta["width"].as_u64(), meta["height"].as_u64()),
        (Some(160), Some(120))
    );
    assert_eq!(meta["lights"], json!(["0", "1"]));
    let (status, bytes) = get(&format!("/api/layer?name=direct&token={token}"), &host);
    assert_eq!((status, bytes.len()), (200, 160 * 120 * 3 * 4));
    let read = read_exr(&exr);
    let first = floats(&bytes)[0];
    assert_eq!(first, read.at("direct.R", 0, 0));
    // Ctrl-C stops it.
    let mut viewer = viewer;
    assert_eq!(viewer.interrupt(), Some(130));

    // With a reference, its beauty is served too, for A/B.
    let other = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "other.exr",
        &["--width", "160", "--height", "120", "--no-shadows"],
    );
    let viewer = Viewer::start_with(
        dir.path(),
        &[
            exr.to_str().expect("utf-8"),
            "--reference",
            other.to_str().expect("utf-8"),
        ],
    );
    let host = format!("127.0.0.1:{}", viewer.port);
    let token = viewer.token().to_string();
    let (_, body) = http(
        viewer.port,
        "GET",
        &format!("/api/image?token={token}"),
        &host,
        None,
    );
    let meta: Value = serde_json::from_slice(&body).expect("json");
    assert_eq!(meta["reference"], true);
    let path = format!("/api/layer?name=beauty&which=reference&token={token}");
    let (status, bytes) = http(viewer.port, "GET", &path, &host, None);
    assert_eq!((status, bytes.len()), (200, 160 * 120 * 4 * 4));
    let first = floats(&bytes)[0];
    assert_eq!(first, read_exr(&other).at("R", 0, 0));
}

/// A WebDriver session on a headless Chromium, ended (and its driver stopped) when dropped.
pub struct Browser {
    driver: Child,
    port: u16,
    session: String,
}

impl Browser {
    pub fn start() -> Browser {
        Browser::start_scaled(1.0)
    }

    /// A browser whose screen has `ratio` device pixels per CSS pixel (a HiDPI screen at 2).
    pub fn start_scaled(ratio: f64) -> Browser {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .map(|a| a.port())
            .expect("a free port");
        let driver = Command::new(tool("chromedriver"))
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts (tools/test installs chromium-driver)");
        let started = Instant::now();
        while TcpStream::connect(("127.0.0.1", port)).is_err() {
            assert!(
                started.elapsed() < Duration::from_secs(20),
                "chromedriver did not listen"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
        let capabilities = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": tool("chromium").to_str().expect("utf-8"),
                "args": ["--headless=new", "--no-sandbox", "--disable-gpu",
                         "--disable-dev-shm-usage", "--window-size=1400,800",
                         format!("--force-device-scale-factor={ratio}")]
            }
        }}});
        let mut browser = Browser {
            driver,
            port,
            session: String::new(),
        };
        let reply = browser.call("POST", "/session", Some(capabilities));
        browser.session = reply["sessionId"]
            .as_str()
            .unwrap_or_else(|| panic!("no session: {reply}"))
            .to_string();
        browser
    }

    pub fn call(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        let host = format!("127.0.0.1:{}", self.port);
        let (status, bytes) = http(self.port, method, path, &host, body.as_ref());
        let reply: Value = serde_json::from_slice(&bytes).expect("WebDriver JSON");
        assert_eq!(status, 200, "{method} {path}: {reply}");
        reply["value"].clone()
    }

    pub fn session(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        self.call(method, &format!("/session/{}{path}", self.session), body)
    }

    pub fn script(&self, script: &str, args: Value) -> Value {
        self.session(
            "POST",
            "/execute/sync",
            Some(json!({"script": script, "args": args})),
        )
    }

    /// Opens `url` and waits until the page says it is ready.
    /// Goes to `url` without waiting for the viewer (any page: a report, the class page).
    pub fn navigate(&self, url: &str) {
        self.session("POST", "/url", Some(json!({"url": url})));
    }

    pub fn open(&self, url: &str) {
        self.session("POST", "/url", Some(json!({"url": url})));
        self.wait_for(
            "!!(window.whitted && window.whitted.ready)",
            "the page is ready",
        );
    }

    /// Waits (up to a minute) until the JavaScript expression `condition` is true.
    pub fn wait_for(&self, condition: &str, what: &str) {
        let started = Instant::now();
        while self.script(&format!("return {condition}"), json!([])) != json!(true) {
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "never true: {what} ({condition})"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// Asserts that the page has had no uncaught error or unhandled rejection.
    pub fn assert_no_errors(&self) {
        let errors = self.script("return window.whitted.errors", json!([]));
        assert_eq!(errors, json!([]), "errors on the page");
    }

    /// The display bytes of the page's canvas at (x, y).
    pub fn canvas_pixel(&self, x: f64, y: f64) -> [u8; 3] {
        let v = self.script(
            "const c = document.getElementById('canvas').getContext('2d'); \
             return Array.from(c.getImageData(arguments[0], arguments[1], 1, 1).data)",
            json!([x, y]),
        );
        let byte = |i: usize| v[i].as_u64().expect("a byte") as u8;
        [byte(0), byte(1), byte(2)]
    }

    /// Saves a screenshot as `name` under target/, and under $WHITTED_SCREENSHOTS when set
    /// (tools/screenshots sets it to docs/images, for the README).
    pub fn screenshot(&self, name: &str) {
        let shot = self.session("GET", "/screenshot", None);
        let bytes = base64_decode(shot.as_str().expect("base64"));
        assert!(bytes.starts_with(b"\x89PNG"), "a PNG screenshot");
        let mut dirs = vec![root().join("target")];
        dirs.extend(std::env::var_os("WHITTED_SCREENSHOTS").map(PathBuf::from));
        for dir in dirs {
            let out = dir.join(name);
            std::fs::write(&out, &bytes).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
        }
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let host = format!("127.0.0.1:{}", self.port);
            let _ = http(
                self.port,
                "DELETE",
                &format!("/session/{}", self.session),
                &host,
                None,
            );
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

pub fn base64_decode(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let digits: Vec<u8> = text
        .bytes()
        .filter(|&c| c != b'=' && !c.is_ascii_whitespace())
        .map(value)
        .collect();
    digits
        .chunks(4)
        .flat_map(|q| {
            let n = q.iter().fold(0u32, |n, &d| n << 6 | u32::from(d)) << (6 * (4 - q.len()));
            let bytes = n.to_be_bytes();
            bytes[1..q.len()].to_vec()
        })
        .collect()
}

#[test]
fn the_page_probes_and_relights_like_the_command_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = small_render(d);
    let viewer = Viewer::start(d, &exr);
    let browser = Browser::start();
    browser.open(&viewer.url);
    // Without --watch the files are read once: the page does not poll for reloads.
    assert_eq!(
        browser.script("return window.whitted.following", json!([])),
        json!(false)
    );

    // The probe shows the EXR's own values.
    let read = read_exr(&exr);
    let probe = browser.script("return window.whitted.probe(40, 70)", json!([]));
    for (layer, channel, name) in [("beauty", 0, "R"), ("direct", 1, "direct.G"), ("Z", 0, "Z")] {
        let shown = probe["values"][layer][channel].as_f64().expect("a number");
        assert_eq!(shown, f64::from(read.at(name, 40, 70)), "{layer}");
    }

    // Light 0 at 0 in the page equals `whitted relight --light 0=0`, to 1 LSB.
    let pixels = browser.script(
        "return window.whitted.setToneMap('tick', 0) \
           .then(() => window.whitted.setGain('0', 0, 0, 0)) \
           .then(() => window.whitted.pixels())",
        json!([]),
    );
    let pixels: Vec<u8> = pixels
        .as_array()
        .expect("bytes")
        .iter()
        .map(|v| v.as_u64().unwrap_or(0) as u8)
        .collect();
    let run = whitted(
        d,
        &[
            "relight",
            exr.to_str().expect("utf-8"),
            "-o",
            "relit.png",
            "--light",
            "0=0",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let png = read_png(&d.join("relit.png"));
    let mut worst = 0;
    for (i, rgb) in png.data.chunks(3).enumerate() {
        for c in 0..3 {
            worst = worst.max(rgb[c].abs_diff(pixels[i * 4 + c]));
        }
    }
    assert!(worst <= 1, "the page differs from relight by {worst} LSB");
    assert!(pixels.iter().any(|&b| b > 0), "a blank canvas");

    // The README's picture of the relit page is made here.
    browser.wait_for("window.whitted.thumbnails", "the thumbnails are drawn");
    browser.screenshot("viewer.png");
    browser.assert_no_errors();
}

/// The little-endian f32s of a layer the viewer sends.
fn floats(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

#[test]
fn tiff_hdr_and_jpeg_open_with_their_own_values() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = small_render(d);
    // The beauty as a float TIFF, a Radiance HDR and an 8-bit JPEG, written by OpenImageIO.
    for (out, extra) in [
        ("beauty.tif", &["-d", "float"][..]),
        ("beauty.hdr", &[][..]),
        ("beauty.jpg", &["-d", "uint8"][..]),
    ] {
        let mut args = vec![s(&exr), "--ch", "R,G,B"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", out]);
        let run = run_tool("oiiotool", &args, d);
        assert!(run.status.success(), "{out}: {}", stderr(&run));
    }
    let read = read_exr(&exr);
    let viewer = Viewer::start_with(d, &["beauty.tif", "--reference", "beauty.hdr"]);
    let meta = viewer.json("/api/image");
    assert_eq!(
        (&meta["width"], &meta["height"]),
        (&json!(160), &json!(120))
    );
    let name = meta["layers"][0]["name"]
        .as_str()
        .expect("a layer")
        .to_string();
    assert_eq!(meta["layers"][0]["channels"], json!(["R", "G", "B"]));
    let layer = |which: &str| {
        let (status, body) = viewer.get(&format!("/api/layer?name={name}&which={which}"));
        assert_eq!(status, 200, "{which}");
        floats(&body)
    };
    let (tiff, hdr) = (layer("main"), layer("reference"));
    assert_eq!((tiff.len(), hdr.len()), (160 * 120 * 3, 160 * 120 * 3));
    for (i, (&t, &h)) in tiff.iter().zip(&hdr).enumerate() {
        let (x, y, c) = (i / 3 % 160, i / 3 / 160, ["R", "G", "B"][i % 3]);
        let exact = read.at(c, x, y);
        // A float TIFF holds the EXR's own floats.
        assert_eq!(t, exact, "TIFF ({x}, {y}) {c}");
        // RGBE keeps 8 bits of mantissa under the pixel's largest channel.
        let largest = (0..3).map(|k| tiff[i / 3 * 3 + k]).fold(0.0f32, f32::max);
        assert!(
            (h - exact).abs() <= largest / 128.0,
            "HDR ({x}, {y}) {c}: {h} vs {exact}"
        );
    }
    // The two differ only by RGBE's rounding, and the viewer counts where.
    let stats = viewer.json(&format!("/api/stats?name={name}&which=absolute-error"));
    assert!(
        stats["differing_pixels"].as_u64().expect("a count") > 0,
        "{stats}"
    );

    // A JPEG opens too, as its decoded bytes.
    let jpeg = Viewer::start_with(d, &["beauty.jpg"]);
    let meta = jpeg.json("/api/image");
    assert_eq!(
        (&meta["width"], &meta["height"]),
        (&json!(160), &json!(120))
    );
    let (status, body) = jpeg.get(&format!("/api/layer?name={name}&which=main"));
    assert_eq!((status, body.len()), (200, 160 * 120 * 3 * 4));
    assert!(floats(&body).iter().all(|v| (0.0..=1.0).contains(v)));
}

/// The page's bytes (RGBA) after `script` (a promise chain ending in `pixels()`).
fn page_bytes(browser: &Browser, script: &str) -> Vec<u8> {
    browser
        .script(script, json!([]))
        .as_array()
        .expect("bytes")
        .iter()
        .map(|v| v.as_u64().unwrap_or(0) as u8)
        .collect()
}

#[test]
fn names_from_the_file_and_non_finite_values_do_not_break_the_page() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // Lights named as an object's own machinery: legal names in a scene.
    let names = d.join("names.xml");
    std::fs::write(
        &names,
        r##"<scene>
  <ambient-light colour="#404040"/>
  <sphere x="0" y="0" z="4" radius="1" colour="#C04020"/>
  <plane x="0" y="-1" z="0" nx="0" ny="1" nz="0" colour="#808080"/>
  <point-light x="-2" y="2" z="1" colour="#FFFFFF" intensity="80" name="constructor"/>
  <point-light x="2" y="2" z="1" colour="#FFFFFF" intensity="80" name="toString"/>
</scene>
"##,
    )
    .expect("scene");
    let size = ["--width", "80", "--height", "60"];
    let full = render_exr(d, &names, "names.exr", &size);
    let aovs = [&size[..], &["--aovs", "light_constructor,light_toString"]].concat();
    let lights_only = render_exr(d, &names, "lights.exr", &aovs);
    let browser = Browser::start();
    let relit = "return window.whitted.setToneMap('tick', 0) \
                 .then(() => window.whitted.setGain('constructor', 0.5, 0.5, 0.5)) \
                 .then(() => window.whitted.setShadows('toString', false)) \
                 .then(() => window.whitted.setGain('toString', 1, 1, 1)) \
                 .then(() => window.whitted.setShadows('toString', true)) \
                 .then(() => window.whitted.pixels())";
    for exr in [&full, &lights_only] {
        let viewer = Viewer::start(d, exr);
        browser.open(viewer.url());
        let pixels = page_bytes(&browser, relit);
        assert_eq!(pixels.len(), 80 * 60 * 4, "{}", exr.display());
        assert!(pixels.iter().any(|&b| b > 0), "a blank canvas");
        if exr == &full {
            // The same image as `whitted relight --light constructor=0.5`, to 1 LSB.
            let run = whitted(
                d,
                &[
                    "relight",
                    s(exr),
                    "-o",
                    "relit.png",
                    "--light",
                    "constructor=0.5",
                ],
            );
            assert!(run.status.success(), "{}", stderr(&run));
            let png = read_png(&d.join("relit.png"));
            let page = &pixels;
            let worst = png
                .data
                .chunks(3)
                .enumerate()
                .flat_map(|(i, rgb)| (0..3).map(move |c| rgb[c].abs_diff(page[i * 4 + c])))
                .max()
                .unwrap_or(0);
            assert!(worst <= 1, "the page differs from relight by {worst}");
        }
    }

    // A NaN and an infinity in the file: the probe says so instead of throwing.
    use exr::prelude::*;
    let mut values = vec![0.25f32; 16];
    values[5] = f32::NAN;
    values[6] = f32::INFINITY;
    let plane = |name: &str, v: &Vec<f32>| AnyChannel::new(name, FlatSamples::F32(v.clone()));
    let mut channels = Vec::new();
    for layer in ["ambient", "light_0", "background"] {
        channels.extend(["R", "G", "B"].map(|c| plane(&format!("{layer}.{c}"), &values)));
    }
    channels.extend(["R", "G", "B"].map(|c| plane(c, &values)));
    let layer = Layer::new(
        (4, 4),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    let odd = d.join("odd.exr");
    Image::from_layer(layer).write().to_file(&odd).expect("exr");
    let viewer = Viewer::start(d, &odd);
    browser.open(viewer.url());
    for (x, y) in [(1, 1), (2, 1)] {
        let probe = browser.script(
            "return window.whitted.probe(arguments[0], arguments[1]) \
               .then(() => document.getElementById('probe').textContent)",
            json!([x, y]),
        );
        let text = probe.as_str().expect("the probe's text");
        assert!(text.contains("non-finite"), "({x}, {y}): {text}");
    }
}

#[test]
fn ctrl_c_while_replies_compute_leaves_no_redirect_page() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = small_render(d);
    let tmp = d.join("tmp");
    std::fs::create_dir(&tmp).expect("tmp");
    // Without --no-browser: the redirect page (which holds the token) is written.
    let mut child = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(["view", exr.to_str().expect("utf-8")])
        .env("TMPDIR", &tmp)
        .current_dir(d)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("whitted view starts");
    let mut line = String::new();
    BufReader::new(child.stdout.take().expect("stdout"))
        .read_line(&mut line)
        .expect("the URL line");
    let pages = || {
        std::fs::read_dir(&tmp)
            .expect("tmp")
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with("whitted-view-"))
            .count()
    };
    // Written just after the URL is printed.
    let started = Instant::now();
    while pages() == 0 {
        assert!(
            started.elapsed() < Duration::from_secs(10),
            "no redirect page"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let port: u16 = line.trim()["http://127.0.0.1:".len()..]
        .split('/')
        .next()
        .and_then(|p| p.parse().ok())
        .expect("a port");
    let token = line
        .trim()
        .split("token=")
        .nth(1)
        .expect("token")
        .to_string();
    // Replies being computed when the signals come.
    for _ in 0..8 {
        let token = token.clone();
        std::thread::spawn(move || {
            let path = format!("/api/stats?name=beauty&which=relative-squared-error&token={token}");
            let _ = http(port, "GET", &path, &format!("127.0.0.1:{port}"), None);
        });
    }
    std::thread::sleep(Duration::from_millis(50));
    for _ in 0..2 {
        let _ = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status();
        std::thread::sleep(Duration::from_millis(20));
    }
    let status = child.wait().expect("wait");
    assert_eq!(status.code(), Some(130));
    assert_eq!(pages(), 0, "the redirect page was left behind");
}

/// A later year's EXR: the page starts on the year's tone map, and a click's ray tree is
/// traced under the year's rules from the embedded scene the EXR records (no `-i` needed).
#[test]
fn a_later_year_s_exr_opens_on_its_tone_map_and_traces_its_rules() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let run = whitted(
        d,
        &[
            "render", "-q", "--course", "2021-22", "--width", "80", "--height", "60", "--no-png",
            "--exr", "y.exr",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let exr = read_exr(&d.join("y.exr"));
    let viewer = Viewer::start(d, &d.join("y.exr"));
    let meta = viewer.json("/api/image");
    assert_eq!(meta["tonemap"], "sigmoid");
    assert_eq!(meta["trees"], true);
    let trees = viewer.json("/api/trees?x=40&y=30");
    for (c, name) in ["R", "G", "B"].iter().enumerate() {
        assert_eq!(
            trees["reference"]["beauty"][c].as_f64(),
            Some(f64::from(exr.at(name, 40, 30))),
            "{name}"
        );
    }
    drop(viewer);
    let old = Viewer::start(d, &small_render(d));
    assert_eq!(old.json("/api/image")["tonemap"], "tick");
}
