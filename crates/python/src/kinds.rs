//! Kinds registered from Python: a [`Registry`] of the library's kinds (listed by
//! `kinds()`) to which `add_body(name, factory)` adds a body kind whose compliance matrix a
//! Python callable makes from the body's keys and its contact points
//! ([`contopt_greens::DenseCompliance`], checked by the library). A scene read with
//! `registry=` may name it; an exception the factory raises comes back as itself.

use std::collections::BTreeSet;
use std::sync::{Arc, Mutex};

use contopt_core::{Error, Interface, Result};
use contopt_greens::{dense_compliance_bytes, DenseCompliance};
use contopt_scene::{own_surface, BodyKind, Chosen, Placement, Takes, ZoneKind};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{array, to_python};
use crate::dense::dense_on;

/// Where a factory's own exception waits for the call that ran the scene to raise it.
pub type Failure = Arc<Mutex<Option<PyErr>>>;

/// The kinds a scene may name (`Scene.from_file(path, registry=reg)`): the library's, and body
/// kinds added from Python.
#[pyclass(module = "contopt")]
pub struct Registry {
    pub(crate) registry: contopt_scene::Registry,
    /// The slots of the factories added, shared with the scenes read with this registry.
    pub(crate) failures: Vec<Failure>,
}

/// A kind's name for the library, which keeps names for the life of the process: each
/// distinct name is stored once however often it is registered.
fn interned(name: &str) -> &'static str {
    static NAMES: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    let mut names = NAMES.lock().unwrap_or_else(|e| e.into_inner());
    match names.get(name) {
        Some(&known) => known,
        None => {
            let leaked: &'static str = Box::leak(name.to_owned().into_boxed_str());
            names.insert(leaked);
            leaked
        }
    }
}

#[pymethods]
impl Registry {
    /// The library's kinds: bodies, zones, gaps, designs and solvers.
    #[staticmethod]
    fn standard() -> Self {
        Self {
            registry: contopt_scene::Registry::standard(),
            failures: vec![],
        }
    }

    /// The registered kinds' names by sort: `bodies`, `zones`, `gaps`, `designs`, `solvers`.
    fn kinds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.registry;
        let d = PyDict::new(py);
        d.set_item("bodies", r.body_kinds().collect::<Vec<_>>())?;
        d.set_item("zones", r.zone_kinds().collect::<Vec<_>>())?;
        d.set_item("gaps", r.gap_kinds().collect::<Vec<_>>())?;
        d.set_item("designs", r.designs().collect::<Vec<_>>())?;
        d.set_item("solvers", r.solvers().collect::<Vec<_>>())?;
        Ok(d)
    }

    /// Adds the body kind `name` (replacing a kind of that name): a body on the zone's surface,
    /// held (no rigid motion), whose compliance is `factory(settings, points_mm, area_mm2)`:
    /// `settings` the body's keys (a dict, less `kind`), `points_mm` the n contact points,
    /// shape (n, 3) [mm] in the zone's order, `area_mm2` their weights, shape (n,) [mm²]; it
    /// returns the compliance [mm/N], shape (n, n), entry [i, j] the displacement into the
    /// body at point i under a unit compressive force at point j, symmetric and positive
    /// definite. It is called when a case is built, on the thread that runs it.
    fn add_body(&mut self, name: &str, factory: Py<PyAny>) {
        let kind = interned(name);
        let failure = Failure::default();
        self.failures.push(failure.clone());
        let factory = Arc::new(factory);
        let registry = std::mem::take(&mut self.registry);
        self.registry = registry.with_body_reader(kind, move |settings| {
            Ok(Arc::new(FactoryBody {
                kind,
                settings: settings.clone(),
                factory: factory.clone(),
                failure: failure.clone(),
            }) as Arc<dyn BodyKind>)
        });
    }

    fn __repr__(&self) -> String {
        format!("{:?}", self.registry)
    }
}

/// A body kind registered from Python: its settings as the scene wrote them and the factory
/// of its compliance.
struct FactoryBody {
    kind: &'static str,
    settings: serde_json::Value,
    factory: Arc<Py<PyAny>>,
    failure: Failure,
}

impl FactoryBody {
    /// The factory's matrix for `interface`, checked by the library; its own exception kept in
    /// the slot and said as an error of the field `factory`.
    fn dense(&self, interface: Interface) -> Result<DenseCompliance> {
        Python::attach(|py| {
            self.made(py, interface).map_err(|e| {
                let said = e.to_string();
                *self.failure.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                Error::invalid("factory", self.kind, said)
            })
        })
    }

    /// `factory(settings, points_mm, area_mm2)` on `interface`, its matrix made a body.
    fn made(&self, py: Python<'_>, interface: Interface) -> PyResult<DenseCompliance> {
        let n = interface.len();
        let points: Vec<f64> = interface.points().iter().flatten().copied().collect();
        let settings = to_python(py, &self.settings)?;
        let points = array(py, points, &[n, 3])?;
        let area = array(py, interface.weights().to_vec(), &[n])?;
        let matrix = self.factory.call1(py, (settings, points, area))?;
        dense_on(py, &self.name(), interface, matrix.bind(py))
    }
}

impl BodyKind for FactoryBody {
    /// Its `name` key, or the kind's.
    fn name(&self) -> String {
        match self.settings.get("name").and_then(|n| n.as_str()) {
            Some(name) => name.to_string(),
            None => self.kind.to_string(),
        }
    }

    /// Anything: the factory's matrix is checked when it is made.
    fn check(&self, _at: &Placement) -> Result<()> {
        Ok(())
    }

    /// The matrix numpy makes, its copy and its Cholesky factor.
    fn memory(&self, at: &Placement) -> Option<u64> {
        let n = at.layout.points()?;
        let numpy = contopt_core::memory::bytes(&[n, n], 8);
        contopt_core::memory::sum(&[numpy, dense_compliance_bytes(n)])
    }

    fn owns_surface(&self) -> bool {
        false
    }

    /// It is held.
    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::Nothing
    }

    fn build(
        &self,
        at: &Placement,
        surface: Option<&Interface>,
    ) -> Result<Box<dyn contopt_core::ElasticBody>> {
        let own = own_surface(at, surface)?;
        Ok(Box::new(self.dense(own)?))
    }
}

/// The first exception a factory of `failures` raised, taken from its slot.
pub fn raised(failures: &[Failure]) -> Option<PyErr> {
    failures
        .iter()
        .find_map(|f| f.lock().unwrap_or_else(|p| p.into_inner()).take())
}
