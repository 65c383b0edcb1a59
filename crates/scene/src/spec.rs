//! What a case of a scene may say, as typed values read straight from its file. Keys carry
//! their units (`_mm`, `_mpa`, `_n`); unknown keys are errors. The settings of the library's
//! own solvers, controllers, optimisations and crowns are read as the library defines them,
//! with the library's defaults; what is the scene's own (the zone, the bodies, the gap, the
//! outputs) is defined here and in the kinds' files.
//!
//! Choices are serde's externally tagged enums, written in a scene either way:
//! `gap = { kind = "sphere", radius_mm = 10.0 }` or `gap = { sphere = { radius_mm = 10.0 } }`,
//! and a choice without settings as a bare name, `solver = "auto"`. The bodies, the zone, the
//! gap, the design method and the solver are the kinds of the scene's [`Registry`], read by it
//! ([`CaseSpec::read`]).

use contopt_input::{InputError, Node, Value};
use contopt_optimise::ControllerSettings;
use contopt_roller::Envelope;
use serde::{Deserialize, Serialize};

use crate::bodies::BodyKind;
pub use crate::contact::{ContactSpec, LoadSpec};
use std::sync::Arc;

use contopt_roller::Roller;

use crate::methods::{Analysis, CaseView, Design};
use crate::region::OmegaVSpec;
use crate::registry::{Chosen, Registry, SolverKind};
use crate::zone::Layout;

/// One case: a scene with its sweep value or its `[[case]]` values put in.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseSpec {
    /// Short name; names the results folder.
    pub name: String,
    /// What the scene shows.
    #[serde(default)]
    pub description: String,
    /// A cylindrical roller bearing around the contact (`[bearing]`): it composes the
    /// contact and the bodies (its roller on the solved raceway) and runs its load cases.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bearing: Option<crate::bearing_spec::BearingSpec>,
    /// How the bodies meet: the contact zone, the initial gap and the load that presses them.
    pub contact: ContactSpec,
    /// The two bodies: the first below the zone (its outward normal is n¹ of eq. 2.1), the
    /// second above it. Kinds of the registry.
    #[serde(skip_deserializing)]
    pub body: Vec<Chosen<dyn BodyKind>>,
    /// The contact solver (default `auto`: Polonsky–Keer on large interfaces and where a body
    /// offers an inverse of its operator, the dense active set on the other small ones). A
    /// solver of the registry.
    #[serde(skip_deserializing, default = "crate::registry::default_solver")]
    pub solver: Chosen<dyn SolverKind>,
    /// The design of the initial gap (none: the contact is analysed as it is).
    #[serde(default)]
    pub optimisation: Option<OptimisationSpec>,
    /// Load cases that share a roller's crown: each case is also solved under every load and
    /// tilt of the envelope (a roller gap only).
    #[serde(default)]
    pub envelope: Option<Envelope>,
    /// Memory the dense matrices of a solve may take \[MB\] (default 2000); past it a dense
    /// solver or the linear programme refuses the case before allocating.
    #[serde(default)]
    pub dense_limit_mb: Option<f64>,
    /// Memory the whole case may take by its estimate before anything is built \[MB\]
    /// (default 4000): bodies, dense matrices, results.
    #[serde(default)]
    pub memory_limit_mb: Option<f64>,
    /// What the results gain beyond the contact pressure.
    #[serde(default)]
    pub output: OutputSpec,
}

/// Where the registry's kinds stand in a case's tree.
const BODY: &str = "body";
const ZONE: &str = "contact.zone";
const GAP: &str = "contact.gap";
const SOLVER: &str = "solver";
const METHOD: &str = "optimisation.method";

impl CaseSpec {
    /// Reads a case's tree: its bodies, zone, gap, design method and solver through
    /// `registry`, the rest by serde; every error at its key. A case without a gap has the
    /// default of its zone and bodies ([`crate::contact::default_for`]).
    pub(crate) fn read(tree: &Node, registry: &Registry) -> Result<Self, InputError> {
        let mut rest = tree.clone();
        let [bodies, zone, gap, solver, method] =
            [BODY, ZONE, GAP, SOLVER, METHOD].map(|path| rest.remove(path));
        let mut spec: CaseSpec = rest.deserialize()?;
        let zone = zone.ok_or_else(|| missing(tree, ZONE))?;
        spec.contact.zone = registry.zone(&zone, ZONE)?;
        let gap = gap.map(|node| registry.gap(&node, GAP)).transpose()?;
        let bodies = bodies.ok_or_else(|| missing(tree, BODY))?;
        let Value::Array(items) = bodies.value() else {
            return Err(InputError::new(
                BODY,
                bodies.span(),
                format!(
                    "invalid type: {}, expected an array of bodies",
                    bodies.value().kind()
                ),
            ));
        };
        spec.body = (items.iter().enumerate())
            .map(|(k, node)| registry.body(node, &format!("{BODY}[{k}]")))
            .collect::<Result<_, _>>()?;
        spec.contact.gap =
            gap.unwrap_or_else(|| crate::contact::default_for(&spec.contact.zone, &spec.body));
        if let Some(node) = solver {
            spec.solver = registry.solver(&node, SOLVER)?;
        }
        if let Some(optimisation) = &mut spec.optimisation {
            let node = method.ok_or_else(|| missing(tree, METHOD))?;
            optimisation.method = registry.design(&node, METHOD)?;
        }
        Ok(spec)
    }
}

/// No design: the contact analysed as it is; the method of an `[optimisation]` before the
/// registry has read it, too (serde's placeholder, replaced by [`CaseSpec::read`]).
fn unread() -> Chosen<dyn Design> {
    let analysis = Arc::new(Analysis);
    Chosen::new("none", serde_json::Value::Null, analysis.clone(), analysis)
}

impl CaseSpec {
    /// The case's design: its `[optimisation] method`, or the contact analysed as it is.
    pub fn design(&self) -> &dyn Design {
        match &self.optimisation {
            Some(opt) => &*opt.method,
            None => &Analysis,
        }
    }

    /// [`CaseSpec::design`] as chosen.
    pub(crate) fn chosen_design(&self) -> Chosen<dyn Design> {
        match &self.optimisation {
            Some(opt) => opt.method.clone(),
            None => unread(),
        }
    }

    /// What the case's design sees of it, on the zone and roller its plan laid out.
    pub(crate) fn view<'a>(
        &'a self,
        layout: &'a Layout,
        roller: Option<&'a Roller>,
    ) -> CaseView<'a> {
        let opt = self.optimisation.as_ref();
        CaseView {
            method: opt.map_or("none", |o| o.method.name()),
            controller: opt.and_then(|o| o.controller.as_ref()),
            omega_v: opt.and_then(|o| o.omega_v.as_ref()),
            profile_axis: opt.and_then(|o| o.profile_axis),
            envelope: self.envelope.as_ref(),
            gap: &*self.contact.gap,
            zone: &self.contact.zone,
            layout,
            roller,
        }
    }
}

/// A key the case must have, at the table that lacks it.
fn missing(tree: &Node, path: &str) -> InputError {
    let (table, key) = path.rsplit_once('.').unwrap_or(("", path));
    let span = tree.get(table).and_then(Node::span);
    InputError::new(path, span, format!("missing field `{key}`"))
}

/// The design of the initial gap (`[optimisation]`, §3): what the pressure must satisfy and
/// the method that finds the gap.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OptimisationSpec {
    /// The method and its settings: `given_load`, `given_displacement`, `linear_programme`,
    /// `load_split`, `envelope_split` (a roller's crown for its whole envelope),
    /// `profile_search` (Fujiwara–Kawase's parameters tuned for the envelope),
    /// `circular_search` (a circular crown's), or a design of the registry.
    #[serde(skip_deserializing, default = "unread")]
    pub method: Chosen<dyn Design>,
    /// The controller v(x) of p ≤ v·p_max (§3.1); every method but the profile search needs
    /// one.
    #[serde(default)]
    pub controller: Option<ControllerSettings>,
    /// Ω_v, where the pressure is prescribed (d = 0, p = v·p_max); the rest of the zone is
    /// Ω_nv (default: all of it; a roller's centre row).
    #[serde(default)]
    pub omega_v: Option<OmegaVSpec>,
    /// Change the profile along this surface axis only (0 or 1: the roller's eq. 3.3); default
    /// at the finite-element face nodes, or at every point (a roller: along its axis).
    #[serde(default)]
    pub profile_axis: Option<usize>,
}

/// What the results gain beyond the contact pressure (`[output]`).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Stresses below the surface (`[output.subsurface]`).
    #[serde(default)]
    pub subsurface: Option<crate::subsurface::SubsurfaceSpec>,
    /// The fields over the meshes of the finite-element bodies under each case's solution —
    /// displacements, nodal stresses, and the contact pressure and gap on the faces — as VTK
    /// files for ParaView (`fields_<case>.vtu`, `contact_<case>.vtu`); on request (default
    /// off): their recovery over the whole meshes costs about as much as a case's design (on
    /// the paper's Table 2 at 72 elements, 0.10 s a case against 0.03–0.14 s). A case without
    /// a finite-element body writes none.
    #[serde(default)]
    pub fields: bool,
}
