//! Where a scene comes from: a file, or a bundled scene by name. A name that is both — a
//! bundled scene and a file or folder of that name here — is refused with the two ways to say
//! which was meant; a name that is neither says where the bundled ones are listed.

use std::path::Path;

use contopt_scene::{Registry, Scene, SceneError, BUNDLED};

/// Why a scene cannot be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SourceError {
    /// The scene itself is bad.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// The name could mean two scenes, or none.
    #[error("{0}")]
    Name(String),
}

/// The scene `argument` names, its kinds `registry`'s: a bundled scene (`bundled`, or a bare
/// name with nothing of that name here), or a file. `command` (`run`, `check`) is the
/// subcommand given, which a refusal repeats in the way out it offers.
pub fn load(
    registry: &Registry,
    argument: &str,
    bundled: bool,
    command: &str,
) -> Result<Scene, SourceError> {
    let is_bundled = BUNDLED.iter().any(|b| b.name == argument);
    if bundled {
        return if is_bundled {
            Ok(registry.bundled(argument)?)
        } else {
            Err(not_bundled(argument))
        };
    }
    let path = Path::new(argument);
    let here = std::fs::symlink_metadata(path).ok();
    let bare = !argument.contains(['/', '\\']) && path.extension().is_none();
    match (is_bundled && bare, here) {
        (true, None) => Ok(registry.bundled(argument)?),
        (true, Some(meta)) => {
            let what = if meta.is_dir() { "folder" } else { "file" };
            Err(SourceError::Name(format!(
                "`{argument}` is both a bundled scene and a {what} here: write \
                 `contopt {command} --bundled {argument}` for the bundled scene, or \
                 `./{argument}` for the {what}"
            )))
        }
        (false, Some(meta)) if meta.is_dir() => Err(SourceError::Name(format!(
            "`{argument}` is a folder, not a scene file (a .toml or .json file); `contopt \
             list` shows the bundled scenes"
        ))),
        (false, Some(_)) => Ok(registry.load(path)?),
        (false, None) => Err(SourceError::Name(format!(
            "no scene file `{argument}`, and no bundled scene of that name: `contopt list` \
             shows the bundled scenes"
        ))),
    }
}

/// The error of a name that is not a bundled scene.
pub fn not_bundled(name: &str) -> SourceError {
    let names: Vec<&str> = BUNDLED.iter().map(|b| b.name).collect();
    SourceError::Name(format!(
        "no bundled scene `{name}`; the bundled scenes are {} (`contopt list`)",
        names.join(", ")
    ))
}
