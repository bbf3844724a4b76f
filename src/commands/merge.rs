//! `whitted merge PARTS... -o FULL.exr`: reassemble `--region` parts into the full frame.

use std::path::{Path, PathBuf};

use crate::cli::MergeArgs;
use crate::error::{Error, Result};
use crate::input::exr::read_flat;
use crate::merge::merge;
use crate::openexr::FlatImage;
use crate::output::atomic::AtomicFile;
use crate::output::destination::{refuse_clashes, STDOUT};
use crate::output::exr::write_image;

pub fn run(args: &MergeArgs) -> Result<()> {
    if args.output.as_os_str() == STDOUT {
        return Err(Error::Usage(
            "merge writes an EXR file; `-o -` (standard output) is not supported, give a file name"
                .into(),
        ));
    }
    let inputs: Vec<&Path> = args.parts.iter().map(PathBuf::as_path).collect();
    refuse_clashes(&inputs, &[&args.output])?;
    let mut output = AtomicFile::create(&args.output)?;
    let parts: Vec<FlatImage> = args.parts.iter().map(|p| read(p)).collect::<Result<_>>()?;
    let merged = merge(&parts, &args.parts)?;
    write_image(output.file(), &merged).map_err(|msg| Error::Exr {
        path: args.output.clone(),
        msg,
    })?;
    output.commit()
}

fn read(path: &Path) -> Result<FlatImage> {
    crate::interrupt::check()?;
    read_flat(path)
}
