//! Tick 1* option 1's judge: the one order in which a bump image is read, whichever way it
//! reached the check (`check -i bump.xml IMAGE`, `check --star bump IMAGE`, a program's run,
//! a project folder, `grade`), so that every way says the same of one image. First whether
//! option 1 was done at all (the scene's Tick 1 render), then whether a deterministic render
//! of the bump method, right or with a catalogued mistake, reproduces it (`bump.rs`), then
//! whether its sphere is shaded flat (the skeleton's stub), and only then, the image being
//! random, whether it is a draw with both options on (`star_both.rs`): of the smooth sphere
//! (option 1 not done) or of the bumped scene. What none of them reproduces is the bump
//! check's unmatched finding.

use crate::check::bump::{self, BumpFinding, FOLLOWS};
use crate::check::star_both::{self, BumpDraw, Drawn};
use crate::check::star_not_done;
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene::Scene;
use whitted_core::star::Star;

/// What option 1's image shows.
#[derive(Debug, Clone, PartialEq)]
pub enum BumpVerdict {
    /// Option 1 not done, which is no mistake: the Tick 1 render (a smooth sphere), a sphere
    /// shaded flat, or a draw of the smooth sphere with soft shadows and depth of field.
    NotDone,
    /// A deterministic image: the bump check's finding (the method or mistake it follows, or
    /// that nothing reproduces it).
    Rendered(BumpFinding),
    /// A random image: a draw of the bumped scene with both options on.
    Drawn(BumpDraw),
}

impl BumpVerdict {
    /// The verdict's name, the same in every report (`--json`'s `"verdict"`).
    pub fn name(&self) -> &'static str {
        match self {
            BumpVerdict::NotDone => "option-not-done",
            BumpVerdict::Rendered(f) => rendered_name(f),
            BumpVerdict::Drawn(d) => drawn_name(d),
        }
    }

    /// Whether nothing wrong was found: one option is enough, so option 1 not done passes.
    pub fn passes(&self) -> bool {
        match self {
            BumpVerdict::NotDone => true,
            BumpVerdict::Rendered(f) => f.passes(),
            BumpVerdict::Drawn(d) => d.passes(),
        }
    }

    /// The check's exit status where the verdict decides it, not the byte comparison with the
    /// correct render: option 1 not done, and a draw (no random image equals any one render).
    /// None for a deterministic image, which the case's rule judges against the correct
    /// method's render.
    pub fn decides(&self) -> Option<bool> {
        match self {
            BumpVerdict::NotDone | BumpVerdict::Drawn(_) => Some(self.passes()),
            BumpVerdict::Rendered(_) => None,
        }
    }

    /// Option 1's state for the progress line.
    pub fn progress(&self) -> &'static str {
        match self {
            BumpVerdict::NotDone => "not done",
            _ if self.passes() => "done",
            _ => "with a mistake",
        }
    }
}

/// The name of a deterministic bump image's verdict.
pub fn rendered_name(finding: &BumpFinding) -> &'static str {
    match (finding.passes(), finding.mistake) {
        (true, _) => "bump-correct",
        (false, Some(_)) if finding.matched >= FOLLOWS => "bump-mistake",
        (false, _) => "bump-unmatched",
    }
}

/// The name of a both-options draw's verdict.
pub fn drawn_name(draw: &BumpDraw) -> &'static str {
    match draw.passes() {
        true => "bump-draw",
        false => "bump-draw-mistake",
    }
}

/// The verdict, and the correct method's render in the parametrisation the bump check found
/// (None when it did not run: the image is the Tick 1 render).
#[derive(Debug, Clone)]
pub struct Judged {
    pub verdict: BumpVerdict,
    pub correct: Option<Rgb8>,
}

/// Judges `image` of the bumped `scene` (its maps in `star`: the handout's, or those of the
/// student's own scene) at `bounces` under `course`, in the module's order.
pub fn judge(
    scene: &Scene,
    star: &Star,
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Judged> {
    let not_done = |correct| Judged {
        verdict: BumpVerdict::NotDone,
        correct,
    };
    if star_not_done::is_tick1_render(scene, image, bounces, course)? {
        return Ok(not_done(None));
    }
    let (finding, correct) = bump::check_bump(scene, star, image, bounces, course)?;
    let correct = Some(correct);
    // Reproduced, rightly or by a catalogued mistake: deterministic, no draw.
    if finding.matched >= FOLLOWS {
        return Ok(Judged {
            verdict: BumpVerdict::Rendered(finding),
            correct,
        });
    }
    if star_not_done::is_flat_sphere(scene, image, bounces, course)? {
        return Ok(not_done(correct));
    }
    let verdict = match star_both::check(scene, star, image, bounces, course)? {
        Some(Drawn::Bumped(draw)) => BumpVerdict::Drawn(draw),
        Some(Drawn::Smooth(_)) => BumpVerdict::NotDone,
        None => BumpVerdict::Rendered(finding),
    };
    Ok(Judged { verdict, correct })
}

#[cfg(test)]
mod tests {
    use super::*;
    use whitted_core::star::BumpMistake;

    fn finding(mistake: Option<BumpMistake>, matched: f64) -> BumpVerdict {
        BumpVerdict::Rendered(BumpFinding {
            parametrisation: "y-zx",
            mistake,
            matched,
            matched_correct: 0.5,
            tried: 48,
        })
    }

    fn draw(mistake: Option<BumpMistake>) -> BumpVerdict {
        BumpVerdict::Drawn(BumpDraw {
            parametrisation: "y-zx",
            mistake,
            statistic: 1.2,
            correct: 3.5,
            tried: 13,
        })
    }

    #[test]
    fn a_draw_and_an_option_not_done_decide_the_exit_status_and_a_render_leaves_it_to_the_bytes() {
        assert_eq!(draw(None).decides(), Some(true));
        assert_eq!(draw(Some(BumpMistake::Inverted)).decides(), Some(false));
        assert_eq!(BumpVerdict::NotDone.decides(), Some(true));
        assert_eq!(finding(None, 1.0).decides(), None);
        assert_eq!(finding(Some(BumpMistake::Inverted), 1.0).decides(), None);
    }

    #[test]
    fn each_verdict_has_its_name_and_progress() {
        let cases = [
            (BumpVerdict::NotDone, "option-not-done", "not done"),
            (finding(None, 0.99), "bump-correct", "done"),
            (
                finding(Some(BumpMistake::Inverted), 0.99),
                "bump-mistake",
                "with a mistake",
            ),
            // The nearest candidate, a mistake, reproduces too little to be named.
            (
                finding(Some(BumpMistake::Inverted), 0.5),
                "bump-unmatched",
                "with a mistake",
            ),
            (draw(None), "bump-draw", "done"),
            (
                draw(Some(BumpMistake::WrongTexel)),
                "bump-draw-mistake",
                "with a mistake",
            ),
        ];
        for (verdict, name, progress) in cases {
            assert_eq!(verdict.name(), name, "{verdict:?}");
            assert_eq!(verdict.progress(), progress, "{verdict:?}");
        }
    }
}
