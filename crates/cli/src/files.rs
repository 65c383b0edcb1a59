//! The results folder: files go only into `<out>/<scene name>/`, never through a symbolic link,
//! each replaced whole (written beside its name, then renamed over it).

use std::fs::OpenOptions;
use std::io::{BufWriter, Error, ErrorKind, Result, Write};
use std::path::{Path, PathBuf};

/// The list of the files a run wrote, kept in the folder for the next run.
pub const MANIFEST: &str = ".contopt-results";

/// Refuses an `--out` that names something other than a folder (a regular file, a link to
/// nothing, a path through a file), before anything is solved.
pub fn check_out(out: &Path) -> Result<()> {
    let refused = |kind, why: &str| {
        Err(Error::new(
            kind,
            format!(
                "--out {} {why}: give the folder the results go to",
                out.display()
            ),
        ))
    };
    match std::fs::metadata(out) {
        Ok(m) if !m.is_dir() => refused(ErrorKind::AlreadyExists, "is a file, not a folder"),
        Ok(_) => Ok(()),
        Err(e) if e.kind() == ErrorKind::NotFound => match std::fs::symlink_metadata(out) {
            Ok(_) => refused(ErrorKind::NotFound, "is a symbolic link to nothing"),
            Err(_) => Ok(()),
        },
        Err(e) => refused(e.kind(), &format!("cannot be a folder ({e})")),
    }
}

/// Refuses, before anything is solved, an output place that [`ResultsDir::create`] would
/// refuse once the cases are solved: `out` as [`check_out`] does, and each of the nested
/// `folders` below it (the scene's, then a shard's) that is a symbolic link or not a folder,
/// or whose name leads elsewhere. The same checks as `create`'s, on what exists now.
pub fn check_place(out: &Path, folders: &[&str]) -> Result<()> {
    check_out(out)?;
    let mut dir = out.to_path_buf();
    for name in folders {
        check_name(name)?;
        dir.push(name);
        if !existing_folder(&dir)? {
            break;
        }
    }
    Ok(())
}

/// Refuses a folder name that is not a plain name ([`contopt_scene::check_name`]).
fn check_name(name: &str) -> Result<()> {
    contopt_scene::check_name(name).map_err(|reason| {
        Error::new(
            ErrorKind::InvalidInput,
            format!("the scene name {name:?} {reason}"),
        )
    })
}

/// Whether `dir` is a folder (false when it is missing), refusing a symbolic link there and
/// anything else that is not a folder.
fn existing_folder(dir: &Path) -> Result<bool> {
    match std::fs::symlink_metadata(dir) {
        Ok(m) if m.file_type().is_symlink() => Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "{} is a symbolic link: results are not written through links",
                dir.display()
            ),
        )),
        Ok(m) if !m.is_dir() => Err(Error::new(
            ErrorKind::AlreadyExists,
            format!("{} exists and is not a folder", dir.display()),
        )),
        Ok(_) => Ok(true),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(false),
        Err(e) => Err(e),
    }
}

/// The folder a scene's results go to, created (with `out`) when missing.
pub struct ResultsDir {
    dir: PathBuf,
    written: Vec<String>,
}

impl ResultsDir {
    /// `out/name`, where `name` passes the scene's own [`contopt_scene::check_name`] (checked
    /// again here, for callers that did not parse a scene) and `out/name` is not a symbolic
    /// link.
    pub fn create(out: &Path, name: &str) -> Result<Self> {
        check_name(name)?;
        std::fs::create_dir_all(out)?;
        let dir = out.join(name);
        if !existing_folder(&dir)? {
            std::fs::create_dir(&dir)?;
        }
        Ok(Self {
            dir,
            written: vec![],
        })
    }

    /// Ends a run: the files the last run wrote here (listed in [`MANIFEST`]) that this run
    /// did not write are removed, so that no stale result survives, and nothing else is
    /// touched; then the list is replaced by this run's.
    pub fn finish(mut self) -> Result<Self> {
        let manifest = self.dir.join(MANIFEST);
        let regular = std::fs::symlink_metadata(&manifest).is_ok_and(|m| m.is_file());
        let previous = if regular {
            std::fs::read_to_string(&manifest)?
        } else {
            String::new()
        };
        for name in previous.lines() {
            let plain = Path::new(name).file_name().is_some_and(|f| f == name);
            if plain && name != MANIFEST && !self.written.iter().any(|w| w == name) {
                let path = self.dir.join(name);
                if std::fs::symlink_metadata(&path).is_ok_and(|m| !m.is_dir()) {
                    std::fs::remove_file(path)?;
                }
            }
        }
        let list = self.written.join("\n") + "\n";
        self.write(MANIFEST, list.as_bytes())?;
        self.written.pop();
        Ok(self)
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
        self.write_with(name, &mut |f| f.write_all(contents))
    }

    /// [`ResultsDir::write`] with the contents streamed by `write` through a buffer.
    pub fn write_with(
        &mut self,
        name: &str,
        write: &mut dyn FnMut(&mut dyn Write) -> Result<()>,
    ) -> Result<()> {
        let target = self.dir.join(name);
        let spare = self
            .dir
            .join(format!(".{name}.{}.part", std::process::id()));
        let written = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&spare)
            .and_then(|f| {
                let mut buffered = BufWriter::new(f);
                write(&mut buffered)?;
                buffered.flush()
            })
            .and_then(|()| std::fs::rename(&spare, &target));
        if written.is_err() {
            let _ = std::fs::remove_file(&spare);
        }
        written?;
        self.written.push(name.to_string());
        Ok(())
    }
}

impl contopt_report::Sink for ResultsDir {
    fn put(&mut self, name: &str, contents: &[u8]) -> Result<()> {
        self.write(name, contents)
    }

    fn put_with(
        &mut self,
        name: &str,
        write: &mut dyn FnMut(&mut dyn Write) -> Result<()>,
    ) -> Result<()> {
        self.write_with(name, write)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        // A re-run that writes fewer files removes the stale one it wrote before, and nothing
        // that is not its own.
        dir.write("dh.svg", b"<svg/>").unwrap();
        std::fs::write(dir.path().join("notes.txt"), "mine").unwrap();
        let dir = dir.finish().unwrap();
        let mut again = ResultsDir::create(&out, "scene").unwrap();
        again.write("p.svg", b"<svg/>").unwrap();
        again.finish().unwrap();
        assert!(!dir.path().join("dh.svg").exists());
        assert!(dir.path().join("p.svg").exists() && dir.path().join("notes.txt").exists());
        std::os::unix::fs::symlink(&root, out.join("linked")).unwrap();
        assert!(ResultsDir::create(&out, "linked").is_err());
        for name in ["..", ".", "a/b", "/abs", ""] {
            assert!(ResultsDir::create(&out, name).is_err(), "{name}");
        }
        std::fs::remove_dir_all(&root).unwrap();
    }
}
