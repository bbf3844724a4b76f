//! whitted-serve: the course's tester as a service (`whitted serve`, docs/serve.md). Each
//! student opens a personal link, uploads the PNGs their program wrote (checked at once, in
//! this process, as `whitted check` checks them) or their project (compiled and run on the
//! year's skeleton in grade's sandbox, queued), and reads the report `check --report` writes;
//! the staff watch the class live and export the latest attempts as `whitted grade` writes
//! its outputs.
//!
//! # What it may depend on
//! whitted-core, whitted-io, whitted-check, whitted-grade (the sandboxed run and the class
//! files), whitted-view (the accept loop and its limits, the Host check), hyper, tokio,
//! rusqlite, maud, multer. Never clap.
//!
//! The parts: `route.rs` parses every request into a closed set; `answer.rs` answers it
//! against the database (`store.rs`, SQLite in WAL mode), deciding who may see what;
//! `server.rs` is the thin hyper adapter on the viewer's accept loop; `worker.rs` runs the
//! queued attempts, a project as a process of its own (`job.rs`, which counts its CPU time in
//! `cpu.rs`) or, with `--slurm`, as a Slurm job (`slurm.rs`); `data.rs` keeps the uploads.

mod answer;
mod cpu;
mod data;
mod db;
mod export;
mod images;
mod job;
mod pages;
mod project;
mod reply;
mod roster;
mod route;
mod scene_choice;
mod secret;
mod server;
mod slurm;
mod staff_view;
mod store;
mod upload;
mod worker;
mod zip_in;

use std::net::{IpAddr, SocketAddr};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

pub use data::DATABASE;

/// What `whitted serve` was asked.
#[derive(Debug, Clone)]
pub struct Config {
    pub course: Course,
    pub listen: SocketAddr,
    pub data: PathBuf,
    pub roster: Option<PathBuf>,
    /// Workers of each kind (image checks, program runs).
    pub jobs: usize,
    /// The address students reach it at through the course's reverse proxy
    /// (`https://tester.example.ac.uk`): its links, and the Host it answers to.
    pub public_url: Option<String>,
    /// A header the trusted proxy sets to the signed-in user (`X-Remote-User`).
    pub trust_user_header: Option<String>,
    /// The proxy's address: the header is read from its connections only.
    pub trusted_proxy: Option<IpAddr>,
    /// The users the header may name who see the staff pages.
    pub staff: Vec<String>,
    /// Seconds each case of a program may take.
    pub seconds: u64,
    /// Projects run as Slurm jobs (`jobs` of them in Slurm at once), not on local workers.
    pub slurm: bool,
}

/// The user header's trust: its name, the one address it is taken from, and the staff.
#[derive(Debug, Clone)]
pub struct ProxyTrust {
    pub header: String,
    pub proxy: IpAddr,
    pub staff: Vec<String>,
}

/// What the server and the workers share.
pub struct App {
    pub data: data::Data,
    pub course: Course,
    pub seconds: u64,
    /// The Host values answered (DNS rebinding), from the listen address and the public URL.
    pub hosts: Vec<String>,
    pub proxy: Option<ProxyTrust>,
    pub bell: worker::Bell,
    /// Whether projects go to Slurm.
    pub slurm: bool,
    /// The service's jobs in Slurm's queue at the last look, with their states.
    pub job_states: std::sync::Mutex<std::collections::HashMap<String, String>>,
}

/// Serves until a signal stops the process.
pub fn serve(config: &Config) -> Result<()> {
    let proxy = match (&config.trust_user_header, config.trusted_proxy) {
        (Some(header), Some(proxy)) => Some(ProxyTrust {
            header: header.to_ascii_lowercase(),
            proxy,
            staff: config.staff.clone(),
        }),
        (None, None) => None,
        _ => {
            return Err(Error::Usage(
                "--trust-user-header and --trusted-proxy go together: the header is trusted \
                 only from the proxy's address"
                    .into(),
            ))
        }
    };
    if config.slurm {
        slurm::check()?;
    }
    // The roster is read and checked before the data folder is made: a wrong --roster leaves
    // nothing behind.
    let members = match &config.roster {
        Some(path) => {
            let text =
                std::fs::read_to_string(path).map_err(|e| Error::io(path, "cannot read", e))?;
            Some(roster::parse(&path.display().to_string(), &text)?)
        }
        None => None,
    };
    let data = data::Data::open(&config.data)?;
    let mut store = store::Store::open(&data.database())?;
    if let Some(members) = &members {
        store.add_roster(members)?;
    }
    let (orphans, requeued) = store.requeue_running(config.slurm)?;
    // Jobs sent to Slurm by a start with --slurm: their attempts run here now.
    slurm::cancel(&orphans);
    let known = store
        .all_attempts()?
        .into_iter()
        .map(|a| a.folder)
        .collect();
    data.sweep(&known)?;
    let listener = std::net::TcpListener::bind(config.listen)
        .map_err(|e| Error::Environment(format!("cannot listen on {}: {e}", config.listen)))?;
    let local = listener
        .local_addr()
        .map_err(|e| Error::Environment(format!("cannot listen: {e}")))?;
    let base = match &config.public_url {
        Some(url) => url.trim_end_matches('/').to_string(),
        None => format!("http://{local}"),
    };
    store.set_meta("base", &base)?;
    store.set_meta("course", config.course.name())?;
    let (staff_secret, _) = store.staff()?;
    let mut hosts = vec![local.to_string()];
    if local.ip().is_loopback() {
        hosts.push(format!("localhost:{}", local.port()));
    }
    if let Some(url) = &config.public_url {
        hosts.push(host_of(url)?);
    }
    let students = store.students()?.len();
    drop(store);
    let app = Arc::new(App {
        data,
        course: config.course,
        seconds: config.seconds,
        hosts,
        proxy,
        bell: worker::Bell::default(),
        slurm: config.slurm,
        job_states: Default::default(),
    });
    worker::start(app.clone(), config.jobs)?;
    if config.slurm {
        slurm::start(app.clone(), config.jobs)?;
    }
    let out = format!(
        "whitted serve: {} for {students} students on http://{local} (data in {}{})\n\
         staff page: {base}/staff/{staff_secret}\n\
         students' links: whitted serve links --data {}",
        whitted_grade::tick(config.course),
        config.data.display(),
        match requeued {
            0 => String::new(),
            n => format!("; {n} interrupted runs queued again"),
        },
        config.data.display(),
    );
    whitted_io::output::stdout::print_line(&out)?;
    let served = server::run(listener, app.clone());
    if app.slurm {
        match slurm::shutdown(&app) {
            Ok(0) => {}
            Ok(n) => eprintln!("whitted serve: {n} Slurm jobs not started were cancelled"),
            Err(e) => eprintln!("whitted serve: {e}"),
        }
    }
    served
}

/// `whitted serve run-attempt DIR`: runs the project attempt whose folder is `dir` (as the
/// service's workers and its Slurm jobs start it), writing its progress and its outcome there.
pub fn run_attempt(dir: &Path) -> Result<()> {
    job::run(dir)
}

/// The `host[:port]` of a URL, as a Host header gives it.
fn host_of(url: &str) -> Result<String> {
    let rest = url
        .strip_prefix("https://")
        .or_else(|| url.strip_prefix("http://"))
        .ok_or_else(|| Error::Usage(format!("--public-url {url}: give it as https://HOST")))?;
    let host = rest.split('/').next().unwrap_or("");
    match host.is_empty() {
        true => Err(Error::Usage(format!("--public-url {url}: no host in it"))),
        false => Ok(host.to_string()),
    }
}

/// `whitted serve links`: the roster with each student's link, then the staff's, as CSV
/// (`id,name,email,link`); a revoked link is empty.
pub fn links(dir: &Path) -> Result<String> {
    let data = data::Data::existing(dir)?;
    let store = store::Store::open(&data.database())?;
    let base = store
        .meta("base")?
        .unwrap_or_else(|| "http://127.0.0.1:8080".into());
    let (staff, _) = store.staff()?;
    let mut out = csv::Writer::from_writer(Vec::new());
    let mut write = |row: [&str; 4]| {
        out.write_record(row)
            .map_err(|e| Error::Environment(format!("cannot write the links: {e}")))
    };
    write(["id", "name", "email", "link"])?;
    for s in store.students()? {
        let link = s
            .secret
            .as_ref()
            .map(|secret| format!("{base}/s/{}-{secret}", s.number))
            .unwrap_or_default();
        write([&s.id, &s.name, &s.email, &link])?;
    }
    write(["staff", "", "", &format!("{base}/staff/{staff}")])?;
    let bytes = out
        .into_inner()
        .map_err(|e| Error::Environment(format!("cannot write the links: {e}")))?;
    Ok(String::from_utf8_lossy(&bytes).trim_end().to_string())
}

/// Revokes `id`'s link, and with `reissue` gives them a new one.
pub fn set_link(dir: &Path, id: &str, reissue: bool) -> Result<()> {
    let data = data::Data::existing(dir)?;
    store::Store::open(&data.database())?.set_link(id, reissue)
}

/// `whitted serve backup FILE`: a consistent copy of the database, while serving.
pub fn backup(dir: &Path, to: &Path) -> Result<()> {
    let data = data::Data::existing(dir)?;
    if to.exists() {
        return Err(Error::Usage(format!(
            "{}: already exists; give a new file for the backup",
            to.display()
        )));
    }
    let partial = to.with_extension("partial");
    // The copy holds every student's link secret: private to its user from its first byte,
    // as the data folder is (SQLite would create it 0644).
    std::os::unix::fs::OpenOptionsExt::mode(
        std::fs::OpenOptions::new().write(true).create_new(true),
        0o600,
    )
    .open(&partial)
    .map_err(|e| match e.kind() {
        std::io::ErrorKind::AlreadyExists => Error::Usage(format!(
            "{}: already exists (left by an interrupted backup?); remove it or give another file",
            partial.display()
        )),
        _ => Error::io(&partial, "cannot create", e),
    })?;
    let done = store::Store::open(&data.database())?
        .backup(&partial)
        .and_then(|()| std::fs::rename(&partial, to).map_err(|e| Error::io(to, "cannot write", e)));
    if done.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    done
}
