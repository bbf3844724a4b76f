//! `whitted merge PARTS... -o FULL.exr`: reassemble `--region` parts into the full frame.

use std::path::{Path, PathBuf};

use crate::cli::MergeArgs;
use whitted_core::error::{Error, Result};
use whitted_io::input::exr::read_flat;
use whitted_io::merge::merge;
use whitted_io::openexr::FlatImage;
use whitted_io::output::atomic::AtomicFile;
use whitted_io::output::destination::{refuse_clashes, STDOUT};
use whitted_io::output::exr::write_image;

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
    whitted_core::interrupt::check()?;
    read_flat(path)
}
