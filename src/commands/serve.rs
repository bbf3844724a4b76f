//! `whitted serve`: the course's tester as a service (docs/serve.md); `serve links`, `revoke`,
//! `reissue` and `backup` work on its data folder. The service is whitted-serve's.

use crate::cli::{ServeAction, ServiceArgs};
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_io::output::stdout;

pub fn run(args: &ServiceArgs) -> Result<()> {
    match &args.action {
        Some(ServeAction::Links(a)) => stdout::print_line(&whitted_serve::links(&a.data)?),
        Some(ServeAction::Revoke(a)) => {
            whitted_serve::set_link(&a.data.data, &a.id, false)?;
            stdout::print_line(&format!(
                "revoked {}'s link: it now opens a page telling them to ask the course staff; \
                 `whitted serve reissue --data {} {}` gives them a new one",
                a.id,
                a.data.data.display(),
                a.id
            ))
        }
        Some(ServeAction::Reissue(a)) => {
            whitted_serve::set_link(&a.data.data, &a.id, true)?;
            stdout::print_line(&whitted_serve::links(&a.data.data)?)
        }
        Some(ServeAction::Backup(a)) => whitted_serve::backup(&a.data.data, &a.file),
        Some(ServeAction::RunAttempt(a)) => whitted_serve::run_attempt(&a.dir),
        None => whitted_serve::serve(&whitted_serve::Config {
            course: Course::from(args.course),
            listen: args.listen,
            data: args.data.clone(),
            roster: args.roster.clone(),
            jobs: usize::from(args.jobs),
            public_url: args.public_url.clone(),
            trust_user_header: args.trust_user_header.clone(),
            trusted_proxy: args.trusted_proxy,
            staff: args.staff.clone(),
            seconds: args.timeout,
            slurm: args.slurm,
        }),
    }
}
