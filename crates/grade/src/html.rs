//! What the pages `grade` writes share: escaping (names and messages come from submissions and
//! must never become markup), images inline as data URIs (a report is one file that can be
//! mailed), and one style sheet. The escaping and the images are `whitted_io::html`'s and the
//! style `check`'s HTML printer's, so that `check --report x.html` and a graded student's page
//! are one page; kept here is what only a class needs: its references encoded once.

use std::collections::HashMap;
use std::sync::Mutex;

use whitted_check::check::print::html::Embed;
pub use whitted_check::check::print::html::STYLE;
pub use whitted_io::html::{escape, image};

/// The images every student's report shows (a case's reference), encoded once per run and
/// kept by what they are: their size, their bytes' fingerprint and their caption.
#[derive(Default)]
pub struct SharedImages {
    encoded: Mutex<HashMap<(u32, u32, String, String), String>>,
}

impl SharedImages {
    /// Images kept: a suite's references, with room for hidden scenes.
    const KEPT: usize = 64;

    /// [`image`] of `rgb`, encoded the first time it is asked for.
    pub fn image(&self, width: u32, height: u32, rgb: &[u8], alt: &str) -> String {
        let key = (
            width,
            height,
            whitted_core::fingerprint::fingerprint(&[rgb]),
            alt.to_string(),
        );
        if let Some(html) = self.encoded.lock().ok().and_then(|c| c.get(&key).cloned()) {
            return html;
        }
        let html = image(width, height, rgb.to_vec(), alt);
        if let Ok(mut c) = self.encoded.lock() {
            if c.len() < Self::KEPT {
                c.insert(key, html.clone());
            }
        }
        html
    }
}

impl Embed for SharedImages {
    fn embed(&self, width: u32, height: u32, rgb: &[u8], alt: &str) -> String {
        self.image(width, height, rgb, alt)
    }
}
