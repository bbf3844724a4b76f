//! `whitted merge PARTS... -o FULL.exr`: reassemble `--region` parts into the full frame.

use std::fs::File;
use std::path::Path;

use crate::cli::MergeArgs;
use crate::error::{Error, Result};
use crate::merge::merge;
use crate::openexr::{self, FlatImage};
use crate::output::atomic::AtomicFile;
use crate::output::exr::write_image;

pub fn run(args: &MergeArgs) -> Result<()> {
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
    let fail = |msg: String| Error::Exr {
        path: path.to_path_buf(),
        msg,
    };
    let file = File::open(path).map_err(|e| Error::io(path, "cannot read", e))?;
    openexr::read_first_part(file).map_err(|e| fail(format!("not a readable OpenEXR file ({e})")))
}
