//! Paths of keys in a document, as errors name them: `contact.load.force_n`, `body[1].material`.

/// A place in a document while it is read, linked back to the root: no allocation until an
/// error renders it.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Path<'a> {
    /// The node a reading started at, with its path already rendered (empty for the document).
    Root(&'a str),
    /// A key of a table.
    Key(&'a Path<'a>, &'a str),
    /// An element of an array.
    Index(&'a Path<'a>, usize),
}

impl Path<'_> {
    /// The path as errors show it.
    pub(crate) fn render(&self) -> String {
        let mut steps = Vec::new();
        let mut at = self;
        let root = loop {
            match at {
                Path::Root(root) => break *root,
                Path::Key(parent, _) | Path::Index(parent, _) => {
                    steps.push(at);
                    at = parent;
                }
            }
        };
        let mut out = root.to_owned();
        for step in steps.iter().rev() {
            match step {
                Path::Key(_, key) => push_key(&mut out, key),
                Path::Index(_, index) => push_index(&mut out, *index),
                Path::Root(_) => {}
            }
        }
        out
    }
}

/// Appends `key` to a rendered path, quoted when it is not a bare TOML key.
pub(crate) fn push_key(out: &mut String, key: &str) {
    if !out.is_empty() {
        out.push('.');
    }
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        out.push_str(key);
    } else {
        out.push_str(&format!("{key:?}"));
    }
}

/// Appends an array index to a rendered path.
pub(crate) fn push_index(out: &mut String, index: usize) {
    out.push_str(&format!("[{index}]"));
}

/// What an error's display puts before its message: `<path>: `, or nothing for the document.
pub(crate) fn prefix(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!("{path}: ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_keys_indices_and_quoted_keys() {
        let root = Path::Root("");
        let body = Path::Key(&root, "body");
        let first = Path::Index(&body, 1);
        let odd = Path::Key(&first, "a.b");
        assert_eq!(Path::Key(&odd, "nu").render(), "body[1].\"a.b\".nu");
        let prefixed = Path::Root("contact");
        assert_eq!(Path::Key(&prefixed, "load").render(), "contact.load");
        assert_eq!(Path::Index(&root, 0).render(), "[0]");
    }
}
