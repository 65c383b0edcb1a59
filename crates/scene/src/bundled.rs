//! The bundled scenes, which the `contopt` command runs by name and prints as templates.

use std::path::Path;

use crate::meshes::MeshFiles;

/// A bundled scene: its name, its text (as in `scenes/<name>.toml`) and the meshes it reads.
#[derive(Clone, Copy, Debug)]
pub struct Bundled {
    /// The name, the file's stem.
    pub name: &'static str,
    /// The TOML text.
    pub text: &'static str,
    /// The mesh files its bodies read, each the path the scene writes (from `scenes/`) and
    /// the file's bytes: built in, so that the scene runs from any folder.
    pub meshes: &'static [(&'static str, &'static [u8])],
}

macro_rules! bundled {
    ($($name:literal $([$($mesh:literal),*])?),* $(,)?) => {
        /// The scenes in `scenes/`, built in.
        pub const BUNDLED: &[Bundled] = &[
            $(Bundled {
                name: $name,
                text: include_str!(concat!("../../../scenes/", $name, ".toml")),
                meshes: &[$($(($mesh, include_bytes!(concat!("../../../scenes/", $mesh)))),*)?],
            }),*
        ];
    };
}

bundled!(
    "paper-table1",
    "paper-table2",
    "paper-table3",
    "roller",
    "roller-study",
    "roller-envelope",
    "bearing",
    "hertz",
    "flat-punch",
    "punch-on-block",
    "steel-on-aluminium",
    "winkler-bed",
    "cylinder-on-block"["../meshes/cylinder-on-block-b8.msh"],
    "filleted-punch"["../meshes/filleted-punch.msh"],
    "shrink-fit"["../meshes/shrink-fit.msh"],
    "sphere-on-solid-block"["../meshes/solid-block-on-grid.msh"],
    "solid-sphere-on-block"["../meshes/solid-sphere-on-block.msh"],
);

/// The bundled scene `name`.
pub fn find(name: &str) -> Option<&'static Bundled> {
    BUNDLED.iter().find(|b| b.name == name)
}

/// The meshes of the bundled scene `scene`, read as if from `file`'s folder.
pub(crate) fn meshes(scene: &Bundled, file: &Path) -> MeshFiles {
    MeshFiles::new(&crate::folder(file), scene.meshes)
}
