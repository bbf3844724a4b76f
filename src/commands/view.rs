//! `whitted view IMAGE [--reference REF] [-i SCENE] [--watch] [--port N] [--no-browser]`: an
//! EXR, or a PNG, JPEG, TIFF or Radiance HDR through the same readers as `info` and `diff`,
//! so that a student's PNG can be set against the reference (`view/content.rs` reads them).

use crate::cli::ViewArgs;
use whitted_core::error::Result;
use whitted_view::{serve, Source};

pub fn run(args: &ViewArgs) -> Result<()> {
    let source = Source::View {
        image: args.input.clone(),
        reference: args.reference.clone(),
        scene: args.scene.clone(),
    };
    let s = &args.serve;
    serve(source, s.port, s.no_browser, s.watch)
}
