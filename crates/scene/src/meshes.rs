//! The mesh files a scene names (a body's `mesh`): where they are read from, and each read
//! once for all the cases of a scene.
//!
//! A mesh is read, never written, so a scene may name one anywhere it could name an include
//! of an FE input deck: a relative path is read from the scene file's folder (`punch.msh`
//! beside it, `meshes/punch.msh` below it, `../meshes/punch.msh` beside its folder, so that
//! a folder of scenes and meshes moves as one), an absolute path as written. It must be a
//! regular file (a link to one is followed): a folder, a device or a pipe is refused before
//! anything is read from it, and Gmsh's reader refuses a file too large for the memory of a
//! body before reading it. A bundled scene's meshes are built into contopt as its text is,
//! found by the path the scene writes, so that it runs from any folder.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use contopt_core::{Error, Result};
use contopt_gmsh::{GmshMesh, ImportedMesh, ImportedSolid, PhysicalName, Surfaces, Volumes};

/// The files a scene's bodies read, and those read so far.
#[derive(Debug)]
pub struct MeshFiles {
    /// The scene file's folder.
    dir: PathBuf,
    /// A bundled scene's meshes: each the path its scene writes and the file's bytes.
    bundled: &'static [(&'static str, &'static [u8])],
    /// The bodies imported so far, by path and surface group.
    read: Mutex<HashMap<BodyKey, Arc<Imported>>>,
    /// The solids imported so far, by path and volume group.
    solids: Mutex<HashMap<BodyKey, Arc<ImportedSolid>>>,
}

/// A body of a mesh file: the file's path as the scene writes it, and its surface group.
type BodyKey = (String, Option<String>);

/// A body imported from a mesh file, with the file's physical names.
#[derive(Debug)]
pub struct Imported {
    /// The body: its elements, nodes and named groups of points and curves.
    pub mesh: ImportedMesh,
    /// Every physical name of the file, of every dimension.
    pub names: Vec<PhysicalName>,
}

impl Imported {
    /// The dimension of the file's physical group `name`, when the file has one.
    pub fn dimension(&self, name: &str) -> Option<usize> {
        self.names.iter().find(|p| p.name == name).map(|p| p.dim)
    }
}

impl MeshFiles {
    /// The meshes of a scene read from a file in `dir`.
    pub fn in_folder(dir: &Path) -> Self {
        Self::new(dir, &[])
    }

    /// The meshes of a bundled scene (read as if from `dir`): `bundled` first, then the folder.
    pub fn new(dir: &Path, bundled: &'static [(&'static str, &'static [u8])]) -> Self {
        Self {
            dir: dir.to_owned(),
            bundled,
            read: Mutex::new(HashMap::new()),
            solids: Mutex::new(HashMap::new()),
        }
    }

    /// The body of the mesh file `path` made of the 2-D physical group `surface` (every
    /// surface when `None`), read and imported on the first call for this path and group.
    /// A file that cannot be read is an error at `mesh`; what Gmsh's import refuses is
    /// [`Error::Mesh`], its message naming the file and the group.
    pub fn import(&self, path: &str, surface: Option<&str>) -> Result<Arc<Imported>> {
        let key = (path.to_string(), surface.map(str::to_string));
        let read = || self.read.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(done) = read().get(&key) {
            return Ok(done.clone());
        }
        let file = self.file(path)?;
        let mesh = file.import(surface.map_or(Surfaces::All, Surfaces::Group))?;
        let imported = Arc::new(Imported {
            mesh,
            names: file.physical_names().to_vec(),
        });
        read().insert(key, imported.clone());
        Ok(imported)
    }

    /// The solid of the mesh file `path` made of the 3-D physical group `volume` (every volume
    /// when `None`), read and imported on the first call for this path and group; errors as
    /// [`MeshFiles::import`]'s, Gmsh's naming the element or the group.
    pub fn import_solid(&self, path: &str, volume: Option<&str>) -> Result<Arc<ImportedSolid>> {
        let key = (path.to_string(), volume.map(str::to_string));
        let read = || self.solids.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(done) = read().get(&key) {
            return Ok(done.clone());
        }
        let solid = Arc::new(
            self.file(path)?
                .import_solid(volume.map_or(Volumes::All, Volumes::Group))?,
        );
        read().insert(key, solid.clone());
        Ok(solid)
    }

    /// The file `path` read by Gmsh's reader: a bundled mesh, or a regular file.
    fn file(&self, path: &str) -> Result<GmshMesh> {
        if path.trim().is_empty() {
            return Err(Error::invalid(
                "mesh",
                format!("{path:?}"),
                "give the Gmsh mesh file (.msh), relative to the scene's folder",
            ));
        }
        if let Some((_, bytes)) = self.bundled.iter().find(|(name, _)| *name == path) {
            return contopt_gmsh::parse(bytes, &self.dir.join(path).display().to_string());
        }
        let resolved = self.dir.join(path);
        let refused = |why: String| Error::invalid("mesh", format!("{path:?}"), why);
        let folder = self.dir.display();
        let metadata = std::fs::metadata(&resolved).map_err(|e| {
            refused(format!(
                "cannot read {} ({e}): a mesh path is read relative to the scene's folder \
                 {folder}",
                resolved.display()
            ))
        })?;
        if !metadata.is_file() {
            return Err(refused(format!(
                "{} is not a regular file: a mesh is a Gmsh file (.msh, MSH 4.1)",
                resolved.display()
            )));
        }
        contopt_gmsh::read(&resolved)
    }
}
