//! `tick1-student YEAR CRSID MISTAKES DIR`: writes a Tick 1 student's `Plane.java`,
//! `Renderer.java` and `Sphere.java` of course year YEAR, in package
//! `uk.ac.cam.cl.gfxintro.CRSID.tick1`, into DIR: whitted's finished Tick 1 with MISTAKES (a
//! comma list of `tests/java/tick1-mistakes.txt`'s ids, empty for none) edited in, exactly as
//! the integration tests write their students. For scripts that build a class of students
//! (tools/bench-grade), so that they need no copy of the fixture nor of its rules.

// The tests' own module: what only the tests use of it is unused here.
#[allow(dead_code)]
#[path = "../tests/integration/tick1_fixture.rs"]
mod tick1_fixture;

use std::path::Path;

fn main() {
    if let Err(message) = run(&std::env::args().skip(1).collect::<Vec<_>>()) {
        eprintln!("tick1-student: {message}");
        std::process::exit(2);
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let [year, crsid, mistakes, dir] = args else {
        return Err("usage: tick1-student YEAR CRSID MISTAKES DIR".into());
    };
    let mistakes: Vec<&str> = mistakes.split(',').filter(|m| !m.is_empty()).collect();
    // Every file first, so that a mistake that cannot be made leaves no file written.
    let files = tick1_fixture::FILES
        .into_iter()
        .map(|name| {
            Ok((
                name,
                tick1_fixture::student_file(name, year, crsid, &mistakes)?,
            ))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let dir = Path::new(dir);
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}
