//! How the bodies of a case meet (`[contact]`): the zone, the initial gap and what presses them
//! together.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::bodies::BodyKind;
use crate::chosen::Chosen;
use crate::gap::{Flat, GapKind, Measured};
pub use crate::load::LoadSpec;
use crate::registry;
use crate::zone::{MeshZone, ZoneKind};

/// How the bodies meet (`[contact]`).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// The proposed contact zone Ω and its discretisation, shared by both bodies: a zone kind
    /// of the scene's [`crate::Registry`].
    #[serde(skip_deserializing, default = "crate::zone::unread")]
    pub zone: Chosen<dyn ZoneKind>,
    /// The initial gap h(x) between the bodies: a gap kind of the scene's
    /// [`crate::Registry`], read with the bodies (default: measured between two imported
    /// meshes on a zone of meshes, else flat).
    #[serde(skip_deserializing, default = "flat")]
    pub gap: Chosen<dyn GapKind>,
    /// What presses the bodies together beyond their own loads (default none).
    #[serde(default)]
    pub load: LoadSpec,
}

/// The gap of a scene that gives none: the distance measured between two imported meshes on a
/// zone of meshes, else flat.
pub(crate) fn default_for(
    zone: &Chosen<dyn ZoneKind>,
    bodies: &[Chosen<dyn BodyKind>],
) -> Chosen<dyn GapKind> {
    let imported = bodies.iter().filter(|b| b.imported()).count();
    if zone.downcast::<MeshZone>().is_some() && imported == 2 {
        chosen("measured", Measured {})
    } else {
        flat()
    }
}

/// The flat gap, as the registry would read `gap = "flat"` (serde's placeholder before
/// [`crate::CaseSpec::read`] reads the gap).
pub(crate) fn flat() -> Chosen<dyn GapKind> {
    chosen("flat", Flat {})
}

/// A gap kind chosen as `name` without a scene's text.
fn chosen<K: GapKind + Serialize + 'static>(name: &'static str, kind: K) -> Chosen<dyn GapKind> {
    let kind = Arc::new(kind);
    let written = registry::written_under(name, &*kind);
    Chosen::new(name, written, kind.clone(), kind)
}

#[cfg(test)]
mod tests {
    use contopt_input::Node;

    use crate::Registry;

    /// The gap a scene that gives none takes is the one `gap = "flat"` reads.
    #[test]
    fn the_default_gap_is_the_flat_one_read() {
        let node = Node::parse_toml("gap = \"flat\"").unwrap();
        let read = Registry::standard()
            .gap(node.get("gap").unwrap(), "gap")
            .unwrap();
        assert_eq!(read, super::flat());
    }
}
