//! The service's database: SQLite in WAL mode (readers never wait for the one writer, and a
//! transaction either is on disk whole or not at all, whenever the process is killed). Four
//! tables: the students with their link secrets and CSRF tokens, the staff's link, the
//! attempts (each upload accepted, with where its files are and how far it got) and the
//! results (one per attempt at most: the primary key is the attempt's, so a run repeated
//! after a crash can never give an attempt two).
//!
//! Each thread opens its own connection (`Store::open`); SQLite serialises the writers, and
//! `busy_timeout` makes one wait rather than fail while another writes.

use std::path::Path;
use std::time::Duration;

use rusqlite::{params, Connection, OptionalExtension};

use super::roster::Member;
use super::secret;
use whitted_core::error::{Error, Result};

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS meta (
    key TEXT PRIMARY KEY,
    value TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS students (
    number INTEGER PRIMARY KEY,
    id TEXT NOT NULL UNIQUE,
    name TEXT NOT NULL DEFAULT '',
    email TEXT NOT NULL DEFAULT '',
    secret TEXT,
    csrf TEXT NOT NULL,
    issued INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS staff (
    one INTEGER PRIMARY KEY CHECK (one = 1),
    secret TEXT NOT NULL,
    csrf TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS attempts (
    id INTEGER PRIMARY KEY,
    student INTEGER NOT NULL REFERENCES students(number),
    kind TEXT NOT NULL CHECK (kind IN ('images', 'project')),
    folder TEXT NOT NULL UNIQUE,
    files TEXT NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('queued', 'running', 'done')),
    received INTEGER NOT NULL,
    started INTEGER,
    finished INTEGER,
    runs INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX IF NOT EXISTS attempts_of ON attempts(student, id);
CREATE INDEX IF NOT EXISTS attempts_queued ON attempts(status, kind, id);
CREATE TABLE IF NOT EXISTS results (
    attempt INTEGER PRIMARY KEY REFERENCES attempts(id),
    passed INTEGER NOT NULL,
    verdict TEXT NOT NULL,
    mistake TEXT,
    finding TEXT NOT NULL,
    progress TEXT NOT NULL,
    report TEXT NOT NULL
);
";

/// Columns added after the first schema, each to a database that lacks it: (table, column,
/// its declaration). A database of an earlier version is brought up at its first open.
const ADDED: [(&str, &str, &str); 2] = [
    // The CPU seconds of everything a project's run started (NULL: not measurable there).
    ("results", "cpu", "REAL"),
    // The Slurm job a project's run was sent to (`--slurm`), while it is in flight.
    ("attempts", "job", "TEXT"),
];

/// What an attempt holds: images checked in process, or a project run in the sandbox.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Images,
    Project,
}

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Images => "images",
            Kind::Project => "project",
        }
    }

    fn of(name: &str) -> Kind {
        match name {
            "project" => Kind::Project,
            _ => Kind::Images,
        }
    }
}

/// How far an attempt got.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Queued,
    Running,
    Done,
}

impl Status {
    pub fn name(self) -> &'static str {
        match self {
            Status::Queued => "queued",
            Status::Running => "running",
            Status::Done => "done",
        }
    }

    fn of(name: &str) -> Status {
        match name {
            "running" => Status::Running,
            "done" => Status::Done,
            _ => Status::Queued,
        }
    }
}

/// A student as the database has them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Student {
    /// The row's number, which the student's link carries beside the secret.
    pub number: i64,
    pub id: String,
    pub name: String,
    pub email: String,
    /// None once the link is revoked.
    pub secret: Option<String>,
    pub csrf: String,
}

/// What a finished attempt found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Outcome {
    pub passed: bool,
    /// One line: how the images compare (or how the program ended).
    pub verdict: String,
    /// The top mistake's catalogue id, when one was diagnosed.
    pub mistake: Option<String>,
    /// Where the mistake is and how to fix it (or why there was nothing to check).
    pub finding: String,
    /// Where the student is in the handout's stages.
    pub progress: String,
    /// The report pages (a JSON list: one per image), as `check --report x.html` writes them.
    pub report: String,
}

/// An attempt with its result when it has one.
#[derive(Debug, Clone)]
pub struct Attempt {
    pub id: i64,
    pub student: i64,
    pub kind: Kind,
    pub folder: String,
    /// The names of the files, as uploaded, one a line.
    pub files: String,
    pub status: Status,
    pub received: i64,
    pub started: Option<i64>,
    pub finished: Option<i64>,
    pub runs: i64,
    pub outcome: Option<Outcome>,
    /// The CPU seconds of all the run started, when it was measured (projects).
    pub cpu: Option<f64>,
    /// The Slurm job running it (`--slurm`).
    pub job: Option<String>,
}

/// Seconds since 1970.
pub fn now() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs() as i64)
}

fn db_error(e: rusqlite::Error) -> Error {
    Error::Environment(format!("the service's database: {e}"))
}

/// One connection to the database.
pub struct Store {
    conn: Connection,
}

const ATTEMPT_COLUMNS: &str = "a.id, a.student, a.kind, a.folder, a.files, a.status, \
     a.received, a.started, a.finished, a.runs, r.passed, r.verdict, r.mistake, r.finding, \
     r.progress, r.report, r.cpu, a.job";

fn attempt_row(row: &rusqlite::Row) -> rusqlite::Result<Attempt> {
    let passed: Option<bool> = row.get(10)?;
    let outcome = match passed {
        None => None,
        Some(passed) => Some(Outcome {
            passed,
            verdict: row.get(11)?,
            mistake: row.get(12)?,
            finding: row.get(13)?,
            progress: row.get(14)?,
            report: row.get(15)?,
        }),
    };
    Ok(Attempt {
        id: row.get(0)?,
        student: row.get(1)?,
        kind: Kind::of(&row.get::<_, String>(2)?),
        folder: row.get(3)?,
        files: row.get(4)?,
        status: Status::of(&row.get::<_, String>(5)?),
        received: row.get(6)?,
        started: row.get(7)?,
        finished: row.get(8)?,
        runs: row.get(9)?,
        outcome,
        cpu: row.get(16)?,
        job: row.get(17)?,
    })
}

fn student_row(row: &rusqlite::Row) -> rusqlite::Result<Student> {
    Ok(Student {
        number: row.get(0)?,
        id: row.get(1)?,
        name: row.get(2)?,
        email: row.get(3)?,
        secret: row.get(4)?,
        csrf: row.get(5)?,
    })
}

const STUDENT_COLUMNS: &str = "number, id, name, email, secret, csrf";

impl Store {
    /// Opens (creating) the database at `path`, in WAL mode, with the schema.
    pub fn open(path: &Path) -> Result<Store> {
        let conn = Connection::open(path).map_err(|e| {
            Error::Environment(format!("cannot open the database {}: {e}", path.display()))
        })?;
        conn.busy_timeout(Duration::from_secs(30))
            .map_err(db_error)?;
        let mode: String = conn
            .query_row("PRAGMA journal_mode=WAL", [], |r| r.get(0))
            .map_err(db_error)?;
        if !mode.eq_ignore_ascii_case("wal") {
            return Err(Error::Environment(format!(
                "{}: the database cannot be put in WAL mode (it is in {mode} mode)",
                path.display()
            )));
        }
        // NORMAL is durable in WAL mode against a killed process (only a power cut may lose
        // the last transactions, never corrupt the database).
        conn.execute_batch("PRAGMA synchronous=NORMAL; PRAGMA foreign_keys=ON;")
            .map_err(db_error)?;
        conn.execute_batch(SCHEMA).map_err(db_error)?;
        for (table, column, declaration) in ADDED {
            let has: bool = conn
                .query_row(
                    &format!(
                        "SELECT count(*) > 0 FROM pragma_table_info('{table}') WHERE name = ?1"
                    ),
                    [column],
                    |r| r.get(0),
                )
                .map_err(db_error)?;
            if !has {
                conn.execute_batch(&format!(
                    "ALTER TABLE {table} ADD COLUMN {column} {declaration}"
                ))
                .map_err(db_error)?;
            }
        }
        Ok(Store { conn })
    }

    /// The journal mode in force (for the tests: `wal`).
    #[cfg(test)]
    pub fn journal_mode(&self) -> Result<String> {
        self.conn
            .query_row("PRAGMA journal_mode", [], |r| r.get(0))
            .map_err(db_error)
    }

    pub fn meta(&self, key: &str) -> Result<Option<String>> {
        self.conn
            .query_row("SELECT value FROM meta WHERE key = ?1", [key], |r| r.get(0))
            .optional()
            .map_err(db_error)
    }

    pub fn set_meta(&self, key: &str, value: &str) -> Result<()> {
        self.conn
            .execute(
                "INSERT INTO meta(key, value) VALUES (?1, ?2) \
                 ON CONFLICT(key) DO UPDATE SET value = excluded.value",
                [key, value],
            )
            .map(drop)
            .map_err(db_error)
    }

    /// Adds the roster's new students, each with a new link; updates the names and emails of
    /// those already there (their links stay). Returns how many were new.
    pub fn add_roster(&mut self, members: &[Member]) -> Result<usize> {
        let tx = self.conn.transaction().map_err(db_error)?;
        let mut added = 0;
        for m in members {
            let inserted = tx
                .execute(
                    "INSERT INTO students(id, name, email, secret, csrf, issued) \
                     VALUES (?1, ?2, ?3, ?4, ?5, ?6) ON CONFLICT(id) DO NOTHING",
                    params![m.id, m.name, m.email, secret::new(), secret::new(), now()],
                )
                .map_err(db_error)?;
            added += inserted;
            if inserted == 0 {
                tx.execute(
                    "UPDATE students SET name = ?2, email = ?3 WHERE id = ?1 \
                     AND (?2 <> '' OR ?3 <> '')",
                    params![m.id, m.name, m.email],
                )
                .map_err(db_error)?;
            }
        }
        tx.commit().map_err(db_error)?;
        Ok(added)
    }

    /// The staff's link secret and CSRF token, made the first time.
    pub fn staff(&self) -> Result<(String, String)> {
        self.conn
            .execute(
                "INSERT INTO staff(one, secret, csrf) VALUES (1, ?1, ?2) \
                 ON CONFLICT(one) DO NOTHING",
                [secret::new(), secret::new()],
            )
            .map_err(db_error)?;
        self.conn
            .query_row("SELECT secret, csrf FROM staff", [], |r| {
                Ok((r.get(0)?, r.get(1)?))
            })
            .map_err(db_error)
    }

    /// Every student, in roster order.
    pub fn students(&self) -> Result<Vec<Student>> {
        let mut statement = self
            .conn
            .prepare(&format!(
                "SELECT {STUDENT_COLUMNS} FROM students ORDER BY number"
            ))
            .map_err(db_error)?;
        let rows = statement
            .query_map([], student_row)
            .map_err(db_error)?
            .collect::<rusqlite::Result<Vec<_>>>();
        rows.map_err(db_error)
    }

    pub fn student(&self, number: i64) -> Result<Option<Student>> {
        self.conn
            .query_row(
                &format!("SELECT {STUDENT_COLUMNS} FROM students WHERE number = ?1"),
                [number],
                student_row,
            )
            .optional()
            .map_err(db_error)
    }

    /// Revokes `id`'s link (`reissue`: gives a new one, the old one dead); Err for an id the
    /// roster does not have.
    pub fn set_link(&self, id: &str, reissue: bool) -> Result<()> {
        let secret = reissue.then(secret::new);
        let changed = self
            .conn
            .execute(
                "UPDATE students SET secret = ?2, csrf = ?3, issued = ?4 WHERE id = ?1",
                params![id, secret, secret::new(), now()],
            )
            .map_err(db_error)?;
        match changed {
            0 => Err(Error::Usage(format!("no student `{id}` in the roster"))),
            _ => Ok(()),
        }
    }

    /// Records an attempt whose files are in `folder` (already in place), queued.
    pub fn add_attempt(&self, student: i64, kind: Kind, folder: &str, files: &str) -> Result<i64> {
        self.conn
            .execute(
                "INSERT INTO attempts(student, kind, folder, files, status, received) \
                 VALUES (?1, ?2, ?3, ?4, 'queued', ?5)",
                params![student, kind.name(), folder, files, now()],
            )
            .map_err(db_error)?;
        Ok(self.conn.last_insert_rowid())
    }

    /// How many attempts `student` made since `since`, and whether one of their projects is
    /// still queued or running.
    pub fn recent(&self, student: i64, since: i64) -> Result<(i64, bool)> {
        self.conn
            .query_row(
                "SELECT (SELECT count(*) FROM attempts WHERE student = ?1 AND received >= ?2), \
                 EXISTS (SELECT 1 FROM attempts WHERE student = ?1 AND kind = 'project' \
                 AND status <> 'done')",
                params![student, since],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .map_err(db_error)
    }

    /// Takes the oldest queued attempt of `kind`, marked running, if there is one.
    pub fn claim(&self, kind: Kind) -> Result<Option<Attempt>> {
        let id: Option<i64> = self
            .conn
            .query_row(
                "UPDATE attempts SET status = 'running', started = ?2, runs = runs + 1 \
                 WHERE id = (SELECT id FROM attempts WHERE status = 'queued' AND kind = ?1 \
                 ORDER BY id LIMIT 1) RETURNING id",
                params![kind.name(), now()],
                |r| r.get(0),
            )
            .optional()
            .map_err(db_error)?;
        match id {
            None => Ok(None),
            Some(id) => self.attempt(id),
        }
    }

    /// Records `outcome` for `attempt` (with the CPU seconds its run took, when measured), and
    /// marks it done, in one transaction.
    pub fn finish(&mut self, attempt: i64, outcome: &Outcome, cpu: Option<f64>) -> Result<()> {
        let tx = self.conn.transaction().map_err(db_error)?;
        tx.execute(
            "INSERT INTO results(attempt, passed, verdict, mistake, finding, progress, report, \
             cpu) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)",
            params![
                attempt,
                outcome.passed,
                outcome.verdict,
                outcome.mistake,
                outcome.finding,
                outcome.progress,
                outcome.report,
                cpu
            ],
        )
        .map_err(db_error)?;
        tx.execute(
            "UPDATE attempts SET status = 'done', finished = ?2, job = NULL WHERE id = ?1",
            params![attempt, now()],
        )
        .map_err(db_error)?;
        tx.commit().map_err(db_error)
    }

    /// After a restart: the attempts that were running when the service stopped are queued
    /// again (their run left nothing in the database), except, with `keep_jobs`, those in
    /// flight on Slurm, whose jobs go on without the service. Returns the requeued attempts'
    /// Slurm jobs (to cancel: a run of the attempt here would race them) and how many.
    pub fn requeue_running(&self, keep_jobs: bool) -> Result<(Vec<String>, usize)> {
        let jobs: Vec<String> = match keep_jobs {
            true => Vec::new(),
            false => self.jobs_in_flight()?.into_iter().map(|(_, j)| j).collect(),
        };
        let n = self
            .conn
            .execute(
                "UPDATE attempts SET status = 'queued', started = NULL, job = NULL \
                 WHERE status = 'running' AND (?1 = 0 OR job IS NULL)",
                [keep_jobs],
            )
            .map_err(db_error)?;
        Ok((jobs, n))
    }

    /// The attempts running as Slurm jobs: (attempt, job).
    pub fn jobs_in_flight(&self) -> Result<Vec<(i64, String)>> {
        let mut statement = self
            .conn
            .prepare("SELECT id, job FROM attempts WHERE status = 'running' AND job IS NOT NULL")
            .map_err(db_error)?;
        let rows = statement
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .map_err(db_error)?
            .collect::<rusqlite::Result<Vec<_>>>();
        rows.map_err(db_error)
    }

    /// Records the Slurm job `attempt` was sent to.
    pub fn set_job(&self, attempt: i64, job: &str) -> Result<()> {
        self.conn
            .execute(
                "UPDATE attempts SET job = ?2 WHERE id = ?1",
                params![attempt, job],
            )
            .map(drop)
            .map_err(db_error)
    }

    /// Queues `attempt` again (its job was cancelled before it ran, or died without a result).
    pub fn requeue(&self, attempt: i64) -> Result<()> {
        self.conn
            .execute(
                "UPDATE attempts SET status = 'queued', started = NULL, job = NULL \
                 WHERE id = ?1 AND status = 'running'",
                [attempt],
            )
            .map(drop)
            .map_err(db_error)
    }

    pub fn attempt(&self, id: i64) -> Result<Option<Attempt>> {
        self.conn
            .query_row(
                &format!(
                    "SELECT {ATTEMPT_COLUMNS} FROM attempts a \
                     LEFT JOIN results r ON r.attempt = a.id WHERE a.id = ?1"
                ),
                [id],
                attempt_row,
            )
            .optional()
            .map_err(db_error)
    }

    /// Every attempt of `student`, newest first.
    pub fn attempts_of(&self, student: i64) -> Result<Vec<Attempt>> {
        self.attempts_where("a.student = ?1 ORDER BY a.id DESC", student)
    }

    /// Every attempt, oldest first (the staff page's history of the class).
    pub fn all_attempts(&self) -> Result<Vec<Attempt>> {
        self.attempts_where("?1 = ?1 ORDER BY a.id", 0)
    }

    fn attempts_where(&self, condition: &str, value: i64) -> Result<Vec<Attempt>> {
        let mut statement = self
            .conn
            .prepare(&format!(
                "SELECT {ATTEMPT_COLUMNS} FROM attempts a \
                 LEFT JOIN results r ON r.attempt = a.id WHERE {condition}"
            ))
            .map_err(db_error)?;
        let rows = statement
            .query_map([value], attempt_row)
            .map_err(db_error)?
            .collect::<rusqlite::Result<Vec<_>>>();
        rows.map_err(db_error)
    }

    /// How many attempts of the same kind are queued before `attempt` (0: it is next).
    pub fn position(&self, attempt: &Attempt) -> Result<i64> {
        self.conn
            .query_row(
                "SELECT count(*) FROM attempts WHERE status = 'queued' AND kind = ?1 AND id < ?2",
                params![attempt.kind.name(), attempt.id],
                |r| r.get(0),
            )
            .map_err(db_error)
    }

    /// A consistent copy of the database in `to`, taken through SQLite's backup API while
    /// the service goes on writing.
    pub fn backup(&self, to: &Path) -> Result<()> {
        let mut copy = Connection::open(to)
            .map_err(|e| Error::Environment(format!("cannot create {}: {e}", to.display())))?;
        let backup = rusqlite::backup::Backup::new(&self.conn, &mut copy).map_err(db_error)?;
        backup
            .run_to_completion(256, Duration::from_millis(5), None)
            .map_err(db_error)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn member(id: &str) -> Member {
        Member {
            id: id.into(),
            name: format!("Name {id}"),
            email: String::new(),
        }
    }

    fn outcome() -> Outcome {
        Outcome {
            passed: false,
            verdict: "differs".into(),
            mistake: Some("no-shadows".into()),
            finding: "f".into(),
            progress: "p".into(),
            report: "<html>".into(),
        }
    }

    #[test]
    fn a_roster_gives_links_that_revoke_and_reissue() {
        let dir = tempfile::tempdir().expect("dir");
        let mut store = Store::open(&dir.path().join("db")).expect("open");
        assert_eq!(store.journal_mode().expect("mode"), "wal");
        assert_eq!(
            store
                .add_roster(&[member("a1"), member("b2")])
                .expect("add"),
            2
        );
        assert_eq!(
            store
                .add_roster(&[member("a1"), member("c3")])
                .expect("add"),
            1
        );
        let students = store.students().expect("students");
        assert_eq!(students.len(), 3);
        let a = &students[0];
        let before = a.secret.clone().expect("a link");
        store.set_link("a1", false).expect("revoked");
        assert_eq!(store.student(a.number).expect("a").expect("a").secret, None);
        store.set_link("a1", true).expect("reissued");
        let after = store
            .student(a.number)
            .expect("a")
            .expect("a")
            .secret
            .expect("new");
        assert_ne!(before, after);
        assert!(store.set_link("zz", true).is_err());
        let (staff, _) = store.staff().expect("staff");
        assert_eq!(store.staff().expect("again").0, staff, "made once");
    }

    #[test]
    fn an_attempt_is_claimed_once_finished_once_and_requeued_after_a_crash() {
        let dir = tempfile::tempdir().expect("dir");
        let mut store = Store::open(&dir.path().join("db")).expect("open");
        store.add_roster(&[member("a1")]).expect("add");
        let number = store.students().expect("s")[0].number;
        let first = store
            .add_attempt(number, Kind::Project, "f1", "A.java")
            .expect("1");
        let second = store
            .add_attempt(number, Kind::Project, "f2", "A.java")
            .expect("2");
        let queued = store.attempt(second).expect("q").expect("q");
        assert_eq!(store.position(&queued).expect("pos"), 1);
        assert!(store.claim(Kind::Images).expect("none").is_none());
        let claimed = store.claim(Kind::Project).expect("c").expect("one");
        assert_eq!(
            (claimed.id, claimed.status, claimed.runs),
            (first, Status::Running, 1)
        );
        // The service dies here; on restart the run is queued again, and runs once more.
        assert_eq!(store.requeue_running(false).expect("requeue").1, 1);
        let again = store.claim(Kind::Project).expect("c").expect("one");
        assert_eq!((again.id, again.runs), (first, 2));
        store.finish(first, &outcome(), Some(6.5)).expect("finish");
        assert!(
            store.finish(first, &outcome(), None).is_err(),
            "never two results"
        );
        let done = store.attempt(first).expect("a").expect("a");
        assert_eq!(done.status, Status::Done);
        assert_eq!(done.outcome, Some(outcome()));
        assert_eq!(done.cpu, Some(6.5));
        assert_eq!(store.recent(number, 0).expect("recent"), (2, true));
        let copy = dir.path().join("copy.sqlite");
        store.backup(&copy).expect("backup");
        let restored = Store::open(&copy).expect("copy");
        assert_eq!(restored.attempts_of(number).expect("a").len(), 2);
    }
}
