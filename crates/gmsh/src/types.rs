//! Gmsh's element types: number, name, dimension and node count, as
//! `gmsh.model.mesh.getElementProperties` gives them (Gmsh 4.15; the types without a fixed
//! node count, polygons, polyhedra and XFEM elements, are left out: a file holding one is
//! refused).

use contopt_core::Error;

/// One of Gmsh's element types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ElementType {
    /// Gmsh's number (`elementType` of `$Elements`).
    pub number: i32,
    /// Gmsh's name ("Quadrilateral 8").
    pub name: &'static str,
    /// Dimension: 0 points, 1 lines, 2 surfaces, 3 volumes.
    pub dim: usize,
    /// Nodes per element.
    pub nodes: usize,
}

impl ElementType {
    const fn new(number: i32, name: &'static str, dim: usize, nodes: usize) -> Self {
        Self {
            number,
            name,
            dim,
            nodes,
        }
    }

    /// The type of Gmsh number `number`, `None` when this reader does not know it.
    pub fn from_number(number: i32) -> Option<Self> {
        TYPES.iter().copied().find(|t| t.number == number)
    }
}

impl std::fmt::Display for ElementType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "type {} ({})", self.number, self.name)
    }
}

/// The 3-node line (start, end, middle) of a face group.
pub(crate) const LINE3: i32 = 8;
/// The 2-node line of a linear mesh.
pub(crate) const LINE2: i32 = 1;
/// The 6-node triangle.
pub(crate) const TRIANGLE6: i32 = 9;
/// The 9-node quadrilateral.
pub(crate) const QUADRANGLE9: i32 = 10;
/// The 8-node quadrilateral.
pub(crate) const QUADRANGLE8: i32 = 16;
/// The linear triangle.
pub(crate) const TRIANGLE3: i32 = 2;
/// The linear quadrilateral.
pub(crate) const QUADRANGLE4: i32 = 3;

const TYPES: [ElementType; 110] = [
    ElementType::new(1, "Line 2", 1, 2),
    ElementType::new(2, "Triangle 3", 2, 3),
    ElementType::new(3, "Quadrilateral 4", 2, 4),
    ElementType::new(4, "Tetrahedron 4", 3, 4),
    ElementType::new(5, "Hexahedron 8", 3, 8),
    ElementType::new(6, "Prism 6", 3, 6),
    ElementType::new(7, "Pyramid 5", 3, 5),
    ElementType::new(8, "Line 3", 1, 3),
    ElementType::new(9, "Triangle 6", 2, 6),
    ElementType::new(10, "Quadrilateral 9", 2, 9),
    ElementType::new(11, "Tetrahedron 10", 3, 10),
    ElementType::new(12, "Hexahedron 27", 3, 27),
    ElementType::new(13, "Prism 18", 3, 18),
    ElementType::new(14, "Pyramid 14", 3, 14),
    ElementType::new(15, "Point", 0, 1),
    ElementType::new(16, "Quadrilateral 8", 2, 8),
    ElementType::new(17, "Hexahedron 20", 3, 20),
    ElementType::new(18, "Prism 15", 3, 15),
    ElementType::new(19, "Pyramid 13", 3, 13),
    ElementType::new(20, "Triangle 9", 2, 9),
    ElementType::new(21, "Triangle 10", 2, 10),
    ElementType::new(22, "Triangle 12", 2, 12),
    ElementType::new(23, "Triangle 15", 2, 15),
    ElementType::new(24, "Triangle 15I", 2, 15),
    ElementType::new(25, "Triangle 21", 2, 21),
    ElementType::new(26, "Line 4", 1, 4),
    ElementType::new(27, "Line 5", 1, 5),
    ElementType::new(28, "Line 6", 1, 6),
    ElementType::new(29, "Tetrahedron 20", 3, 20),
    ElementType::new(30, "Tetrahedron 35", 3, 35),
    ElementType::new(31, "Tetrahedron 56", 3, 56),
    ElementType::new(32, "Tetrahedron 22", 3, 22),
    ElementType::new(33, "Tetrahedron 28", 3, 28),
    ElementType::new(36, "Quadrilateral 16", 2, 16),
    ElementType::new(37, "Quadrilateral 25", 2, 25),
    ElementType::new(38, "Quadrilateral 36", 2, 36),
    ElementType::new(39, "Quadrilateral 12", 2, 12),
    ElementType::new(40, "Quadrilateral 16I", 2, 16),
    ElementType::new(41, "Quadrilateral 20", 2, 20),
    ElementType::new(42, "Triangle 28", 2, 28),
    ElementType::new(43, "Triangle 36", 2, 36),
    ElementType::new(44, "Triangle 45", 2, 45),
    ElementType::new(45, "Triangle 55", 2, 55),
    ElementType::new(46, "Triangle 66", 2, 66),
    ElementType::new(47, "Quadrilateral 49", 2, 49),
    ElementType::new(48, "Quadrilateral 64", 2, 64),
    ElementType::new(49, "Quadrilateral 81", 2, 81),
    ElementType::new(50, "Quadrilateral 100", 2, 100),
    ElementType::new(51, "Quadrilateral 121", 2, 121),
    ElementType::new(52, "Triangle 18", 2, 18),
    ElementType::new(53, "Triangle 21I", 2, 21),
    ElementType::new(54, "Triangle 24", 2, 24),
    ElementType::new(55, "Triangle 27", 2, 27),
    ElementType::new(56, "Triangle 30", 2, 30),
    ElementType::new(57, "Quadrilateral 24", 2, 24),
    ElementType::new(58, "Quadrilateral 28", 2, 28),
    ElementType::new(59, "Quadrilateral 32", 2, 32),
    ElementType::new(60, "Quadrilateral 36I", 2, 36),
    ElementType::new(61, "Quadrilateral 40", 2, 40),
    ElementType::new(62, "Line 7", 1, 7),
    ElementType::new(63, "Line 8", 1, 8),
    ElementType::new(64, "Line 9", 1, 9),
    ElementType::new(65, "Line 10", 1, 10),
    ElementType::new(66, "Line 11", 1, 11),
    ElementType::new(71, "Tetrahedron 84", 3, 84),
    ElementType::new(72, "Tetrahedron 120", 3, 120),
    ElementType::new(73, "Tetrahedron 165", 3, 165),
    ElementType::new(74, "Tetrahedron 220", 3, 220),
    ElementType::new(75, "Tetrahedron 286", 3, 286),
    ElementType::new(79, "Tetrahedron 34", 3, 34),
    ElementType::new(80, "Tetrahedron 40", 3, 40),
    ElementType::new(81, "Tetrahedron 46", 3, 46),
    ElementType::new(82, "Tetrahedron 52", 3, 52),
    ElementType::new(83, "Tetrahedron 58", 3, 58),
    ElementType::new(84, "Line 1", 1, 1),
    ElementType::new(85, "Triangle 1", 2, 1),
    ElementType::new(86, "Quadrilateral 1", 2, 1),
    ElementType::new(87, "Tetrahedron 1", 3, 1),
    ElementType::new(88, "Hexahedron 1", 3, 1),
    ElementType::new(89, "Prism 1", 3, 1),
    ElementType::new(92, "Hexahedron 64", 3, 64),
    ElementType::new(93, "Hexahedron 125", 3, 125),
    ElementType::new(94, "Hexahedron 216", 3, 216),
    ElementType::new(95, "Hexahedron 343", 3, 343),
    ElementType::new(96, "Hexahedron 512", 3, 512),
    ElementType::new(97, "Hexahedron 729", 3, 729),
    ElementType::new(98, "Hexahedron 1000", 3, 1000),
    ElementType::new(99, "Hexahedron 32", 3, 32),
    ElementType::new(100, "Hexahedron 44", 3, 44),
    ElementType::new(101, "Hexahedron 56", 3, 56),
    ElementType::new(102, "Hexahedron 68", 3, 68),
    ElementType::new(103, "Hexahedron 80", 3, 80),
    ElementType::new(104, "Hexahedron 92", 3, 92),
    ElementType::new(105, "Hexahedron 104", 3, 104),
    ElementType::new(118, "Pyramid 30", 3, 30),
    ElementType::new(119, "Pyramid 55", 3, 55),
    ElementType::new(120, "Pyramid 91", 3, 91),
    ElementType::new(121, "Pyramid 140", 3, 140),
    ElementType::new(122, "Pyramid 204", 3, 204),
    ElementType::new(123, "Pyramid 285", 3, 285),
    ElementType::new(124, "Pyramid 385", 3, 385),
    ElementType::new(125, "Pyramid 21", 3, 21),
    ElementType::new(126, "Pyramid 29", 3, 29),
    ElementType::new(127, "Pyramid 37", 3, 37),
    ElementType::new(128, "Pyramid 45", 3, 45),
    ElementType::new(129, "Pyramid 53", 3, 53),
    ElementType::new(130, "Pyramid 61", 3, 61),
    ElementType::new(131, "Pyramid 69", 3, 69),
    ElementType::new(132, "Pyramid 1", 3, 1),
    ElementType::new(137, "Tetrahedron 16", 3, 16),
];

/// The error of a linear element: the mesh must be of order 2.
pub(crate) fn linear(source: &str, tag: u64, t: ElementType) -> Error {
    Error::Mesh(format!(
        "{source}: Gmsh element {tag} is of {t}, a linear element: contopt's elements are \
         quadratic: set `Mesh.ElementOrder = 2;` (and `Mesh.SecondOrderIncomplete = 1;` for \
         8-node quadrilaterals), or run `gmsh -order 2`"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The types the reader converts, by the numbers the MSH format documents.
    #[test]
    fn known_types() {
        let q8 = ElementType::from_number(QUADRANGLE8).unwrap();
        assert_eq!((q8.dim, q8.nodes), (2, 8));
        assert_eq!(q8.to_string(), "type 16 (Quadrilateral 8)");
        assert_eq!(ElementType::from_number(QUADRANGLE9).unwrap().nodes, 9);
        assert_eq!(ElementType::from_number(TRIANGLE6).unwrap().nodes, 6);
        assert_eq!(ElementType::from_number(LINE3).unwrap().nodes, 3);
        assert_eq!(ElementType::from_number(15).unwrap().dim, 0);
        assert_eq!(ElementType::from_number(34), None);
    }
}
