//! `contopt merge`: the shards of a job array (`contopt run --shard K/N`) joined into the files
//! one run of the scene writes. The files drawn from all cases together (`result.json`,
//! `interface.csv`, the charts of p and Δh) are written anew from the joined report; the files
//! of each case (its maps, sections, fields), which the shard wrote already under the case's
//! number in the whole scene, are copied as the shard wrote them, in the scene's order.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use contopt_results::shard::{self, Located, Partial};

use crate::files::{ResultsDir, MANIFEST};
use crate::{fail, finish, Print, EXIT_WRITE};

/// The file of a shard's partial result, in its folder.
pub const PARTIAL: &str = "partial.json";

/// Why shards cannot be merged.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// A shard's folder or file cannot be read.
    #[error("{}: {source}", path.display())]
    Read {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A partial result is not one (its line and column said).
    #[error("{}: not a partial result of contopt run --shard: {source}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// Why.
        source: serde_json::Error,
    },
    /// A folder holds neither a partial result nor shards.
    #[error(
        "{}: no {PARTIAL} and no shard_K_of_N folders in it: give the folders that \
         `contopt run --shard K/N` wrote",
        .0.display()
    )]
    NoShards(PathBuf),
    /// The shards do not make one run.
    #[error("{0}")]
    Shards(#[from] shard::ShardError),
}

/// Merges the shards in `given` (their folders, or folders holding them) into
/// `<out>/<scene>/`, prints the report as `run` does; the exit code.
pub fn merge(given: &[PathBuf], print: Print, out: &Path) -> ExitCode {
    if let Err(e) = crate::files::check_out(out) {
        eprintln!("error: {e}");
        return ExitCode::from(EXIT_WRITE);
    }
    let folders = match shard_folders(given) {
        Ok(folders) => folders,
        Err(e) => return fail(&e),
    };
    let read = folders
        .iter()
        .map(|f| read_partial(f).map(|p| (f.clone(), p)))
        .collect::<Result<Vec<_>, _>>();
    let mut parts = match read {
        Ok(parts) => parts,
        Err(e) => return fail(&e),
    };
    parts.sort_by_key(|(_, p)| p.shard.index);
    let folders: Vec<PathBuf> = parts.iter().map(|(f, _)| f.clone()).collect();
    let located: Vec<Located> = parts
        .into_iter()
        .map(|(f, p)| (f.join(PARTIAL).display().to_string(), p))
        .collect();
    let report = match shard::merge(located) {
        Ok(report) => report,
        Err(e) => return fail(&MergeError::from(e)),
    };
    let files: Vec<Vec<PathBuf>> = match folders.iter().map(|f| case_files(f)).collect() {
        Ok(files) => files,
        Err(e) => return fail(&e),
    };
    let written = ResultsDir::create(out, &report.scene).and_then(|mut dir| {
        contopt_report::write_scene(&report, &mut dir)?;
        copy_case_files(&files, &mut dir)?;
        dir.finish()
    });
    finish(&report, print, written, &out.join(&report.scene))
}

/// The shards' folders: each given folder holding a [`PARTIAL`], and the `shard_K_of_N`
/// folders (sorted by name) of a given folder without one.
fn shard_folders(given: &[PathBuf]) -> Result<Vec<PathBuf>, MergeError> {
    let mut folders = vec![];
    for path in given {
        if path.join(PARTIAL).is_file() {
            folders.push(path.clone());
            continue;
        }
        let read = |source| MergeError::Read {
            path: path.clone(),
            source,
        };
        let mut inner: Vec<PathBuf> = std::fs::read_dir(path)
            .map_err(read)?
            .filter_map(Result::ok)
            .filter(|e| is_shard_name(&e.file_name().to_string_lossy()))
            .map(|e| e.path())
            .filter(|p| p.join(PARTIAL).is_file())
            .collect();
        if inner.is_empty() {
            return Err(MergeError::NoShards(path.clone()));
        }
        inner.sort();
        folders.append(&mut inner);
    }
    Ok(folders)
}

/// Whether `name` is a shard's folder, `shard_K_of_N`.
fn is_shard_name(name: &str) -> bool {
    let numbers = name
        .strip_prefix("shard_")
        .and_then(|rest| rest.split_once("_of_"));
    numbers.is_some_and(|(k, n)| k.parse::<usize>().is_ok() && n.parse::<usize>().is_ok())
}

/// The partial result in `folder`.
fn read_partial(folder: &Path) -> Result<Partial, MergeError> {
    let path = folder.join(PARTIAL);
    let text = std::fs::read_to_string(&path).map_err(|source| MergeError::Read {
        path: path.clone(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| MergeError::Parse { path, source })
}

/// The files of a shard's cases, as its run listed them in its [`MANIFEST`] (all it wrote but
/// its [`PARTIAL`]), each checked to be there.
fn case_files(folder: &Path) -> Result<Vec<PathBuf>, MergeError> {
    let manifest = folder.join(MANIFEST);
    let list = std::fs::read_to_string(&manifest).map_err(|source| MergeError::Read {
        path: manifest,
        source,
    })?;
    list.lines()
        .filter(|name| *name != PARTIAL && Path::new(name).file_name().is_some_and(|f| f == *name))
        .map(|name| {
            let path = folder.join(name);
            match std::fs::symlink_metadata(&path) {
                Ok(m) if m.is_file() => Ok(path),
                Ok(_) => Err(MergeError::Read {
                    path,
                    source: std::io::Error::other("not a regular file"),
                }),
                Err(source) => Err(MergeError::Read { path, source }),
            }
        })
        .collect()
}

/// Copies each shard's case files into the merged folder, shard after shard, one at a time.
fn copy_case_files(files: &[Vec<PathBuf>], dir: &mut ResultsDir) -> std::io::Result<()> {
    for path in files.iter().flatten() {
        let bytes = std::fs::read(path)?;
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        dir.write(&name, &bytes)?;
    }
    Ok(())
}
