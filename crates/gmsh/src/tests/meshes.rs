//! The meshes of `meshes/`, made by Gmsh from the `.geo` files beside them: counts, groups,
//! chains, bounding boxes and areas against the geometry.

use std::f64::consts::PI;

use super::{check_chain, committed, group};
use crate::body::Body;
use crate::geometry::{self, Orientation};
use crate::{Group, Surfaces};
use contopt_fem::ElementKind as Kind;

/// Relative round-off of an area summed over a few hundred elements.
const AREA_ROUND_OFF: f64 = 1e-12;

/// The body and groups of a committed mesh.
fn prepared(name: &str, surfaces: Surfaces) -> (Body, Vec<Group>) {
    committed(name)
        .prepare(surfaces)
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Number of elements of each kind.
fn kinds(body: &Body) -> [usize; 3] {
    let mut n = [0; 3];
    for (kind, _) in &body.elements {
        n[match kind {
            Kind::Q8 => 0,
            Kind::Q9 => 1,
            Kind::T6 => 2,
        }] += 1;
    }
    n
}

/// The bounding box of the body's nodes.
fn bounding_box(body: &Body) -> [[f64; 2]; 2] {
    body.nodes.iter().fold(
        [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]],
        |[lo, hi], p| {
            [
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            ]
        },
    )
}

/// The area between a circular arc of radius `r` and angle `theta` and the parabola through
/// its ends and its middle (the 3-node face with its nodes on the arc): the geometric error of
/// one quadratic face on an arc, r²[(θ − sin θ)/2 − (4/3) sin(θ/2)(1 − cos(θ/2))] ≈ r²θ⁵/960.
fn arc_error(r: f64, theta: f64) -> f64 {
    r * r
        * ((theta - theta.sin()) / 2.0
            - 4.0 / 3.0 * (theta / 2.0).sin() * (1.0 - (theta / 2.0).cos()))
}

/// The geometric error of a group's faces on the circle of `centre` and radius `r` (faces
/// whose three nodes lie on it to round-off): Σ arc_error, and the number of such faces.
/// Gmsh puts a face's middle node within 10⁻⁹ rad of the arc's middle (3·10⁻¹⁰ found); off
/// it by δ, the face's area changes by O(r²θδ²), far below round-off.
fn arc_faces_error(body: &Body, g: &Group, centre: [f64; 2], r: f64) -> (f64, usize) {
    let on = |n: usize| {
        let p = body.nodes[n];
        ((p[0] - centre[0]).hypot(p[1] - centre[1]) - r).abs() < 1e-12 * r
    };
    // The angle between the radii to nodes n and m.
    let angle = |n: usize, m: usize| {
        let (p, q) = (body.nodes[n], body.nodes[m]);
        let (u, v) = (
            [p[0] - centre[0], p[1] - centre[1]],
            [q[0] - centre[0], q[1] - centre[1]],
        );
        (u[0] * v[1] - u[1] * v[0])
            .atan2(u[0] * v[0] + u[1] * v[1])
            .abs()
    };
    let mut total = (0.0, 0);
    for &f in &g.faces {
        let [a, m, b] = body.face_nodes(f);
        if on(a) && on(m) && on(b) {
            let (theta, half) = (angle(a, b), angle(a, m));
            assert!(
                (half - theta / 2.0).abs() < 1e-9,
                "mid node at the arc's middle"
            );
            total.0 += arc_error(r, theta);
            total.1 += 1;
        }
    }
    total
}

/// The 40 × 20 mm rectangle's body and groups, for its Q8 and Q9 versions: counts, the chain
/// of every curve group in the direction that leaves the body on its left (bottom left to
/// right, top right to left), the contact zone inside the top, the area 800 mm² to round-off
/// (straight edges: the quadratic elements fill the rectangle exactly).
fn check_rectangle(name: &str, kind: Kind, nodes: usize) {
    let gmsh = committed(name);
    assert_eq!(
        (
            gmsh.coords().len(),
            gmsh.element_count(2),
            gmsh.element_count(1)
        ),
        (nodes, 110, 40)
    );
    let (body, groups) = prepared(name, Surfaces::All);
    assert_eq!(body.nodes.len(), nodes, "every node is used");
    assert_eq!(body.elements.len(), 110);
    assert!(body.elements.iter().all(|(k, _)| *k == kind));
    assert_eq!(bounding_box(&body), [[0.0, 0.0], [40.0, 20.0]]);
    let area = body.area();
    assert!((area - 800.0).abs() < AREA_ROUND_OFF * 800.0, "area {area}");
    for g in &groups {
        if g.dim == 1 {
            assert_eq!(
                g.faces.len(),
                g.elements_in_file,
                "{}: every line a face",
                g.name
            );
            assert_eq!(check_chain(&body, g), 1, "{}: one chain", g.name);
            assert_eq!(g.nodes.len(), 2 * g.faces.len() + 1, "{}", g.name);
        }
    }
    let x = |n: usize| body.nodes[n][0];
    let y = |n: usize| body.nodes[n][1];
    let bottom = &group(&groups, "bottom").nodes;
    assert!(bottom.iter().all(|&n| y(n) == 0.0));
    assert!(
        bottom.windows(2).all(|w| x(w[0]) < x(w[1])),
        "bottom runs left to right"
    );
    assert_eq!((x(bottom[0]), x(*bottom.last().unwrap())), (0.0, 40.0));
    let top = &group(&groups, "top").nodes;
    assert!(top.iter().all(|&n| y(n) == 20.0));
    assert!(
        top.windows(2).all(|w| x(w[0]) > x(w[1])),
        "top runs right to left"
    );
    let contact = group(&groups, "contact");
    assert!(contact
        .faces
        .iter()
        .all(|f| group(&groups, "top").faces.contains(f)));
    assert_eq!(
        (x(contact.nodes[0]), x(*contact.nodes.last().unwrap())),
        (30.0, 10.0)
    );
    let origin = &group(&groups, "origin").nodes;
    assert_eq!(origin.len(), 1);
    assert_eq!(body.nodes[origin[0]], [0.0, 0.0]);
}

#[test]
fn rectangle_of_8_node_quadrilaterals() {
    check_rectangle("rectangle-q8.msh", Kind::Q8, 371);
}

#[test]
fn rectangle_of_9_node_quadrilaterals() {
    check_rectangle("rectangle-q9.msh", Kind::Q9, 481);
}

/// The public import gives the body's mesh: same nodes, elements and tags; and its extent
/// and area as the body's.
#[test]
fn import_gives_the_prepared_body() {
    for name in [
        "rectangle-q8.msh",
        "rectangle-q9.msh",
        "two-bodies.msh",
        "plate-hole-t6.msh",
        "mixed.msh",
    ] {
        let gmsh = committed(name);
        let surfaces = if name == "two-bodies.msh" {
            Surfaces::Group("punch")
        } else {
            Surfaces::All
        };
        let (body, groups) = gmsh.prepare(surfaces).unwrap();
        let imported = gmsh.import(surfaces).unwrap();
        assert_eq!(imported.mesh.nodes(), &body.nodes[..]);
        let elements: Vec<Vec<usize>> = body.elements.iter().map(|(_, c)| c.clone()).collect();
        assert_eq!(imported.mesh.elements(), &elements[..]);
        assert_eq!(
            (&imported.node_tags, &imported.element_tags),
            (&body.node_tags, &body.element_tags)
        );
        assert_eq!(imported.groups, groups);
        assert!((imported.area() - body.area()).abs() < AREA_ROUND_OFF * body.area());
        assert_eq!(imported.bounding_box(), bounding_box(&body));
    }
}

/// The quarter plate with a hole, in 6-node triangles: its surface is meshed clockwise by
/// Gmsh (curve loop drawn clockwise) and renumbered counter-clockwise. Its area differs from
/// the exact 2500 − 25π mm² by the geometric error of the faces on the arc, each a parabola
/// through three points of the circle: Σ r²[(θ − sin θ)/2 − (4/3) sin(θ/2)(1 − cos(θ/2))], to
/// round-off (mid nodes on the chord instead of the arc would make it Σ r²(θ − sin θ)/2,
/// 80 times larger at these angles). The body is outside the circle, so the mesh is larger.
#[test]
fn plate_with_a_hole_of_6_node_triangles() {
    let gmsh = committed("plate-hole-t6.msh");
    assert_eq!(
        (
            gmsh.coords().len(),
            gmsh.element_count(2),
            gmsh.element_count(1)
        ),
        (878, 413, 51)
    );
    let first = gmsh.blocks().iter().find(|b| b.dim() == 2).unwrap();
    let (_, nodes) = first.elements().next().unwrap();
    let x: Vec<[f64; 2]> = nodes
        .iter()
        .map(|&n| [gmsh.coords()[n][0], gmsh.coords()[n][1]])
        .collect();
    assert_eq!(
        geometry::orientation(Kind::T6, &x),
        Orientation::Clockwise,
        "Gmsh's orientation"
    );

    let (body, groups) = prepared("plate-hole-t6.msh", Surfaces::All);
    assert_eq!(kinds(&body), [0, 0, 413]);
    assert_eq!(bounding_box(&body), [[0.0, 0.0], [50.0, 50.0]]);
    for g in groups.iter().filter(|g| g.dim == 1) {
        assert_eq!(check_chain(&body, g), 1, "{}", g.name);
    }
    let hole = group(&groups, "hole");
    let (error, on_arc) = arc_faces_error(&body, hole, [0.0, 0.0], 10.0);
    assert_eq!(on_arc, hole.faces.len());
    assert_eq!(
        body.nodes[hole.nodes[0]],
        [0.0, 10.0],
        "the hole runs clockwise round the origin"
    );
    let exact = 2500.0 - 25.0 * PI;
    let area = body.area();
    assert!(error > 0.0 && error < 1e-6 * exact, "{error}");
    assert!(
        (area - exact - error).abs() < AREA_ROUND_OFF * exact,
        "{area} − {exact} vs {error}"
    );
    assert_eq!(body.nodes[group(&groups, "corner").nodes[0]], [50.0, 50.0]);
}

/// A mixed mesh, 8-node quadrilaterals left of x = 20 and 6-node triangles right of it,
/// conforming on x = 20 (no duplicate nodes, the shared side inside): area 800 mm² to
/// round-off; "bottom" spans both surfaces as one chain from (0, 0) to (40, 0).
#[test]
fn mixed_quadrilaterals_and_triangles() {
    let (body, groups) = prepared("mixed.msh", Surfaces::All);
    assert_eq!(body.nodes.len(), 315);
    assert_eq!(kinds(&body), [45, 0, 73]);
    let area = body.area();
    assert!((area - 800.0).abs() < AREA_ROUND_OFF * 800.0, "area {area}");
    let bottom = group(&groups, "bottom");
    assert_eq!(check_chain(&body, bottom), 1);
    let ends = [bottom.nodes[0], *bottom.nodes.last().unwrap()];
    assert_eq!(ends.map(|n| body.nodes[n]), [[0.0, 0.0], [40.0, 0.0]]);
    assert_eq!(bottom.faces.len(), bottom.elements_in_file);
    for g in groups.iter() {
        assert_eq!(check_chain(&body, g), 1, "{}", g.name);
    }
}

/// Both bodies of a contact in one file, imported one by one: the base (area 1200 mm²) and
/// the punch with rounded edges, its area 300 − (4 − π)·9/2 mm² less the geometric error
/// of its faces on the two arcs (the body inside the circles). Each body's groups hold only
/// its own faces; the other's are empty on it.
#[test]
fn two_bodies_in_one_file() {
    let (base, groups) = prepared("two-bodies.msh", Surfaces::Group("base"));
    assert!((base.area() - 1200.0).abs() < AREA_ROUND_OFF * 1200.0);
    assert_eq!(bounding_box(&base), [[-30.0, -20.0], [30.0, 0.0]]);
    assert_eq!(check_chain(&base, group(&groups, "base_top")), 1);
    assert!(group(&groups, "punch_face").faces.is_empty());

    let (punch, groups) = prepared("two-bodies.msh", Surfaces::Group("punch"));
    assert_eq!(bounding_box(&punch), [[-10.0, 0.0], [10.0, 15.0]]);
    assert!(group(&groups, "base_top").faces.is_empty());
    let face = group(&groups, "punch_face");
    assert_eq!(check_chain(&punch, face), 1);
    let ends = [face.nodes[0], *face.nodes.last().unwrap()].map(|n| punch.nodes[n]);
    assert_eq!(
        ends,
        [[-10.0, 3.0], [10.0, 3.0]],
        "left to right, the body above"
    );
    let (left, n_left) = arc_faces_error(&punch, face, [-7.0, 3.0], 3.0);
    let (right, n_right) = arc_faces_error(&punch, face, [7.0, 3.0], 3.0);
    assert!(n_left > 0 && n_right > 0);
    let exact = 300.0 - (4.0 - PI) * 9.0 / 2.0;
    let area = punch.area();
    assert!(
        (area - (exact - left - right)).abs() < AREA_ROUND_OFF * exact,
        "{area} vs {exact}"
    );
    assert_eq!(
        base.nodes.len() + punch.nodes.len(),
        committed("two-bodies.msh").coords().len()
    );
}

/// A binary file gives the same content as its ASCII twin, and the same bodies: tags,
/// groups and connectivity alike, coordinates to the 16 significant digits Gmsh writes in
/// ASCII (its binary files hold the full doubles).
#[test]
fn ascii_and_binary_alike() {
    let close = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= 1e-15 * x.abs().max(1.0))
    };
    for name in ["rectangle-q8", "plate-hole-t6", "mixed"] {
        let ascii = committed(&format!("{name}.msh"));
        let binary = committed(&format!("{name}-binary.msh"));
        assert!(!ascii.is_binary() && binary.is_binary());
        assert_eq!(ascii.physical_names(), binary.physical_names(), "{name}");
        assert_eq!(ascii.entities(), binary.entities(), "{name}");
        assert_eq!(ascii.node_tags(), binary.node_tags(), "{name}");
        assert_eq!(ascii.blocks(), binary.blocks(), "{name}");
        assert!(
            close(
                ascii.coords().as_flattened(),
                binary.coords().as_flattened()
            ),
            "{name}"
        );
        let (a, b) = (
            ascii.prepare(Surfaces::All).unwrap(),
            binary.prepare(Surfaces::All).unwrap(),
        );
        assert_eq!(
            (a.0.elements, a.0.element_tags, a.1),
            (b.0.elements, b.0.element_tags, b.1),
            "{name}"
        );
        assert!(
            close(a.0.nodes.as_flattened(), b.0.nodes.as_flattened()),
            "{name}"
        );
    }
}

/// A mesh drawn in metres is 1000 times smaller than the 40 × 20 mm stated; a mesh in mm
/// stated in inches' worth is 25.4 times larger; a plain mismatch says by how much.
#[test]
fn extent_in_other_units() {
    let metres = committed("rectangle-metres.msh")
        .import(Surfaces::All)
        .unwrap();
    let e = metres
        .check_extent([40.0, 20.0], 0.01)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("the mesh is 1000 times smaller than stated: is it in metres?"),
        "{e}"
    );
    assert!(e.contains("rectangle-metres.msh"), "{e}");
    let mm = committed("rectangle-q8.msh").import(Surfaces::All).unwrap();
    mm.check_extent([40.0, 20.0], 1e-9).unwrap();
    let e = mm
        .check_extent([40.0 * 25.4, 20.0 * 25.4], 0.01)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("25.4 times smaller than stated: is it in inches?"),
        "{e}"
    );
    let e = mm.check_extent([40.0, 30.0], 0.01).unwrap_err().to_string();
    assert!(
        e.contains(
            "differs from the stated one by more than 1%: its extent is 40 × 20, stated 40 × 30 mm"
        ),
        "{e}"
    );
    assert!(mm.check_extent([40.0, -1.0], 0.01).is_err());
    assert!(mm.check_extent([40.0, 20.0], 1.5).is_err());
}

/// Two squares meshed separately along their shared side: duplicate nodes, refused with the
/// Gmsh command that joins them.
#[test]
fn duplicate_nodes_are_refused() {
    let e = committed("duplicate-nodes.msh")
        .import(Surfaces::All)
        .unwrap_err()
        .to_string();
    assert!(e.contains("lie at one point (10, "), "{e}");
    assert!(e.contains("`Coherence Mesh;`"), "{e}");
}
