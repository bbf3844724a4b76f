//! The default text report fits one screen (`SCREEN_LINES`): it is made of blocks, those a
//! student needs to act (the verdict, the progress, the finding with where and fix, a line
//! per case) and those that help if there is room (where the differences lie, a program's
//! last error line). When the blocks are too many, the helpful ones go first, last first; the
//! rest is `--verbose`'s, the JSON's and the report file's.

/// Lines the default text report may take: a terminal's screen, with room for the prompt.
pub const SCREEN_LINES: usize = 30;

/// Whether a block must be shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    Always,
    IfRoom,
}

/// Blocks of lines, in the order they are printed.
#[derive(Debug, Default)]
pub struct Screen {
    blocks: Vec<(Keep, Vec<String>)>,
}

impl Screen {
    pub fn push(&mut self, keep: Keep, lines: impl IntoIterator<Item = String>) {
        self.blocks.push((keep, lines.into_iter().collect()));
    }

    pub fn line(&mut self, keep: Keep, line: impl Into<String>) {
        self.push(keep, [line.into()]);
    }

    fn count(&self) -> usize {
        self.blocks.iter().map(|(_, b)| b.len()).sum()
    }

    /// Every line (`max` None), or at most `max`: the blocks kept only if there is room are
    /// left out, last first, until the rest fits; if even what must be shown does not, its
    /// end gives way to a line saying how many more `--verbose` shows.
    pub fn render(mut self, max: Option<usize>) -> String {
        if let Some(max) = max {
            while self.count() > max {
                let Some(i) = self.blocks.iter().rposition(|(k, _)| *k == Keep::IfRoom) else {
                    break;
                };
                self.blocks.remove(i);
            }
        }
        let mut lines: Vec<String> = self.blocks.into_iter().flat_map(|(_, b)| b).collect();
        if let Some(max) = max.filter(|&m| lines.len() > m && m > 0) {
            let more = lines.len() - (max - 1);
            lines.truncate(max - 1);
            lines.push(format!("... {more} lines more: --verbose shows them"));
        }
        lines.join("\n")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbered(prefix: &str, n: usize) -> Vec<String> {
        (0..n).map(|i| format!("{prefix}{i}")).collect()
    }

    #[test]
    fn what_helps_gives_way_last_first_and_what_must_be_shown_stays() {
        let mut screen = Screen::default();
        screen.push(Keep::Always, numbered("a", 10));
        screen.push(Keep::IfRoom, numbered("b", 5));
        screen.push(Keep::Always, numbered("c", 10));
        screen.push(Keep::IfRoom, numbered("d", 8));
        let text = screen.render(Some(SCREEN_LINES));
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 25, "{text}");
        assert!(lines.contains(&"b4") && !lines.contains(&"d0"), "{text}");
    }

    #[test]
    fn too_much_that_must_be_shown_is_cut_with_a_pointer_to_verbose() {
        let mut screen = Screen::default();
        screen.push(Keep::Always, numbered("a", 40));
        let text = screen.render(Some(SCREEN_LINES));
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), SCREEN_LINES);
        assert_eq!(lines[29], "... 11 lines more: --verbose shows them");
        let mut all = Screen::default();
        all.push(Keep::IfRoom, numbered("a", 40));
        assert_eq!(all.render(None).lines().count(), 40);
    }
}
