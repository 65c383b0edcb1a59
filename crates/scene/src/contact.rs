//! How the bodies of a case meet (`[contact]`): the zone, the initial gap and what presses them
//! together.

use serde::{Deserialize, Serialize};

use crate::gap::GapKind;
use crate::registry::Chosen;
use crate::zone::ZoneKind;

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
    #[serde(skip_deserializing, default = "crate::gap::flat")]
    pub gap: Chosen<dyn GapKind>,
    /// What presses the bodies together beyond their own loads (default none).
    #[serde(default)]
    pub load: LoadSpec,
}

/// What presses the bodies together through the contact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadSpec {
    /// Nothing beyond the bodies' own loads (a finite-element punch's pressure on its top).
    #[default]
    None,
    /// A force \[N\] on the second body, which floats along the contact normal (eq. 2.10).
    ForceN(f64),
    /// The second body pushed in by a given approach \[mm\]: it enters the initial gap, h − δ.
    ApproachMm(f64),
}
