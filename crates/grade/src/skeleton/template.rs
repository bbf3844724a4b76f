//! One set of Java sources for the four Tick 1 skeletons (`skeleton/tick1/README.md`): a year is
//! a parameter of those files, never a copy of them. A line ending in `//@SET` is kept only for
//! the skeletons in SET; `//@if SET` ... `//@end` keeps a block; `${WIDTH}` and `${HEIGHT}` are
//! the year's image size. SET is `T2`, `T2+`, `T1-T2`, or a comma list of those.

use whitted_core::course::Api;

/// `text` as the skeleton `api` has it, at image size `size`; or why the template is malformed
/// (a marker that names no skeleton, an unclosed or stray block: the templates' own tests
/// select every file for every skeleton, so this never reaches a user).
pub fn select(text: &str, api: Api, size: (u32, u32)) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    let mut block: Option<bool> = None;
    for (number, line) in text.lines().enumerate() {
        let at = |why: &str| format!("line {}: {why}", number + 1);
        let trimmed = line.trim();
        if let Some(set) = trimmed.strip_prefix("//@if ") {
            if block.is_some() {
                return Err(at("a block inside a block"));
            }
            block = Some(contains(set, api).ok_or_else(|| at("no skeleton set"))?);
            continue;
        }
        if trimmed == "//@end" {
            if block.take().is_none() {
                return Err(at("//@end with no //@if"));
            }
            continue;
        }
        if block == Some(false) {
            continue;
        }
        // A marker is `//@` and a set at the end of a line; `//@` before other words (a
        // comment that names the markers) is text.
        let marker = line
            .rfind("//@")
            .filter(|&at| looks_like_set(&line[at + 3..]));
        let kept = match marker {
            Some(marker) => match contains(&line[marker + 3..], api) {
                Some(true) => Some(line[..marker].trim_end()),
                Some(false) => None,
                None => return Err(at("a marker that names no skeleton set")),
            },
            None => Some(line),
        };
        if let Some(kept) = kept {
            out.push_str(kept);
            out.push('\n');
        }
    }
    if block.is_some() {
        return Err("an //@if block not closed".into());
    }
    Ok(out
        .replace("${WIDTH}", &size.0.to_string())
        .replace("${HEIGHT}", &size.1.to_string()))
}

/// Whether `text` is written as a set is (`T`, digits, `+`, `-`, `,`, blanks), even a wrong one.
fn looks_like_set(text: &str) -> bool {
    let text = text.trim();
    !text.is_empty() && text.chars().all(|c| "T0123456789+-, ".contains(c))
}

/// Whether `set` (`T2`, `T2+`, `T1-T2`, comma separated) holds `api`; None when it is no set.
fn contains(set: &str, api: Api) -> Option<bool> {
    let mut any = false;
    for part in set.trim().split(',') {
        let part = part.trim();
        let (low, high) = if let Some(low) = part.strip_suffix('+') {
            (named(low)?, Api::T4)
        } else if let Some((low, high)) = part.split_once('-') {
            (named(low)?, named(high)?)
        } else {
            (named(part)?, named(part)?)
        };
        any |= (low..=high).contains(&api);
    }
    Some(any)
}

fn named(name: &str) -> Option<Api> {
    Api::TICK1.into_iter().find(|api| api.name() == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_blocks_are_kept_for_their_skeletons_only() {
        let text = "a\nb //@T2+\nc //@T1-T2\n//@if T4, T1\nd\n//@end\ne ${WIDTH}x${HEIGHT} //@T3\n";
        let of = |api| select(text, api, (640, 480)).expect("template");
        assert_eq!(of(Api::T1), "a\nc\nd\n");
        assert_eq!(of(Api::T2), "a\nb\nc\n");
        assert_eq!(of(Api::T3), "a\nb\ne 640x480\n");
        assert_eq!(of(Api::T4), "a\nb\nd\n");
    }

    #[test]
    fn a_malformed_template_is_refused_with_its_line() {
        assert_eq!(
            select("x //@T5\n", Api::T1, (1, 1)),
            Err("line 1: a marker that names no skeleton set".into())
        );
        assert!(select("//@if T1\n", Api::T1, (1, 1)).is_err());
        let prose = "/* markers such as `//@T3+`: see the README */\n";
        assert_eq!(select(prose, Api::T1, (1, 1)), Ok(prose.into()));
        assert!(select("//@end\n", Api::T1, (1, 1)).is_err());
        assert!(select("//@if T1\n//@if T2\n//@end\n//@end\n", Api::T1, (1, 1)).is_err());
    }
}
