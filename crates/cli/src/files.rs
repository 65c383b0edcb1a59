//! The results folder: files go only into `<out>/<scene name>/`, never through a symbolic link,
//! each replaced whole (written beside its name, then renamed over it).

use std::fs::OpenOptions;
use std::io::{Error, ErrorKind, Result, Write};
use std::path::{Path, PathBuf};

/// The folder a scene's results go to, created (with `out`) when missing.
pub struct ResultsDir {
    dir: PathBuf,
    written: Vec<String>,
}

impl ResultsDir {
    /// `out/name`, where `name` is a plain file name (the scene checks it; checked again here)
    /// and `out/name` is not a symbolic link.
    pub fn create(out: &Path, name: &str) -> Result<Self> {
        let plain = Path::new(name)
            .file_name()
            .is_some_and(|f| f == name && name != "." && name != "..");
        if !plain {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!("the scene name {name:?} is not a plain file name"),
            ));
        }
        std::fs::create_dir_all(out)?;
        let dir = out.join(name);
        match std::fs::symlink_metadata(&dir) {
            Ok(m) if m.file_type().is_symlink() => {
                return Err(Error::new(
                    ErrorKind::InvalidInput,
                    format!(
                        "{} is a symbolic link: results are not written through links",
                        dir.display()
                    ),
                ))
            }
            Ok(m) if !m.is_dir() => {
                return Err(Error::new(
                    ErrorKind::AlreadyExists,
                    format!("{} exists and is not a folder", dir.display()),
                ))
            }
            Ok(_) => {}
            Err(e) if e.kind() == ErrorKind::NotFound => std::fs::create_dir(&dir)?,
            Err(e) => return Err(e),
        }
        Ok(Self {
            dir,
            written: vec![],
        })
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// The files written so far, in order.
    pub fn written(&self) -> &[String] {
        &self.written
    }

    /// Writes `contents` as the file `name` in the folder: into a new file beside it (created
    /// exclusively, so never through a link), then renamed over `name`, which replaces a link
    /// there instead of following it. A failed write leaves the old file as it was.
    pub fn write(&mut self, name: &str, contents: &[u8]) -> Result<()> {
        let target = self.dir.join(name);
        let spare = self
            .dir
            .join(format!(".{name}.{}.part", std::process::id()));
        let written = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&spare)
            .and_then(|mut f| f.write_all(contents))
            .and_then(|()| std::fs::rename(&spare, &target));
        if written.is_err() {
            let _ = std::fs::remove_file(&spare);
        }
        written?;
        self.written.push(name.to_string());
        Ok(())
    }
}

/// A CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, a quote or a
/// line break; as it is otherwise.
pub fn csv_field(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\"")).into()
    } else {
        text.into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_are_quoted_when_needed() {
        assert_eq!(csv_field("l1_mm = 20"), "l1_mm = 20");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_field("two\nlines"), "\"two\nlines\"");
    }

    /// A link at a result's name is replaced, its target untouched; a linked scene folder is
    /// refused; names that lead elsewhere are refused.
    #[cfg(unix)]
    #[test]
    fn links_are_not_followed() {
        let root = std::env::temp_dir().join(format!("contopt-files-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let out = root.join("out");
        let mut dir = ResultsDir::create(&out, "scene").unwrap();
        let victim = root.join("victim.txt");
        std::fs::write(&victim, "keep").unwrap();
        std::os::unix::fs::symlink(&victim, dir.path().join("p.svg")).unwrap();
        dir.write("p.svg", b"<svg/>").unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
        assert_eq!(std::fs::read(dir.path().join("p.svg")).unwrap(), b"<svg/>");
        assert_eq!(dir.written(), ["p.svg"]);
        std::os::unix::fs::symlink(&root, out.join("linked")).unwrap();
        assert!(ResultsDir::create(&out, "linked").is_err());
        for name in ["..", ".", "a/b", "/abs", ""] {
            assert!(ResultsDir::create(&out, name).is_err(), "{name}");
        }
        std::fs::remove_dir_all(&root).unwrap();
    }
}
