//! The content of an MSH 4.1 file as Gmsh wrote it: physical names, entities with their
//! physical tags, nodes and element blocks; and the reader of its sections.

use std::collections::HashMap;

use contopt_core::Result;

use crate::cursor::{Cursor, Encoding, RecordBytes};
use crate::types::ElementType;

/// The MSH version read.
const VERSION: &str = "4.1";
/// How to save a mesh in that version, for the error that refuses another.
const SAVE_AS_41: &str = "save it as MSH 4.1: `gmsh -format msh41`, `Mesh.MshFileVersion = 4.1;` \
                          in the .geo, or `gmsh.option.setNumber(\"Mesh.MshFileVersion\", 4.1)`";

/// A node-tag index is a dense table when the header's tag range is at most this many times
/// the node count (plus [`DENSE_SPAN_EXTRA`]); sparser tags go to a hash map.
const DENSE_SPAN_FACTOR: u64 = 4;
/// See [`DENSE_SPAN_FACTOR`].
const DENSE_SPAN_EXTRA: u64 = 1024;

/// A named physical group (`$PhysicalNames`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PhysicalName {
    /// Dimension: 0 points, 1 curves, 2 surfaces, 3 volumes.
    pub dim: usize,
    /// The physical tag.
    pub tag: i32,
    /// The name.
    pub name: String,
}

/// A geometrical entity (`$Entities`): a point, curve, surface or volume, and the physical
/// groups it belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entity {
    /// Dimension: 0 points, 1 curves, 2 surfaces, 3 volumes.
    pub dim: usize,
    /// The entity's tag.
    pub tag: i32,
    /// Tags of the physical groups it belongs to.
    pub physical_tags: Vec<i32>,
}

/// The elements of one type on one entity (a block of `$Elements`).
#[derive(Clone, Debug, PartialEq)]
pub struct ElementBlock {
    dim: usize,
    entity: i32,
    element_type: ElementType,
    tags: Vec<u64>,
    nodes: Vec<usize>,
}

impl ElementBlock {
    /// Dimension of the entity.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Tag of the entity.
    pub fn entity(&self) -> i32 {
        self.entity
    }

    /// The elements' type.
    pub fn element_type(&self) -> ElementType {
        self.element_type
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.tags.len()
    }

    /// True without elements.
    pub fn is_empty(&self) -> bool {
        self.tags.is_empty()
    }

    /// Gmsh's element tags.
    pub fn tags(&self) -> &[u64] {
        &self.tags
    }

    /// The elements: each its Gmsh tag and its nodes, as indices into
    /// [`GmshMesh::coords`], in Gmsh's local order.
    pub fn elements(&self) -> impl Iterator<Item = (u64, &[usize])> + '_ {
        self.tags
            .iter()
            .copied()
            .zip(self.nodes.chunks_exact(self.element_type.nodes))
    }
}

/// The content of an MSH 4.1 file. Element nodes are resolved to indices into
/// [`GmshMesh::coords`] as the file is read.
#[derive(Clone, Debug, PartialEq)]
pub struct GmshMesh {
    source: String,
    binary: bool,
    physical_names: Vec<PhysicalName>,
    entities: Vec<Entity>,
    node_tags: Vec<u64>,
    coords: Vec<[f64; 3]>,
    blocks: Vec<ElementBlock>,
}

impl GmshMesh {
    /// The file's name, as errors quote it.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// True for a binary file.
    pub fn is_binary(&self) -> bool {
        self.binary
    }

    /// The named physical groups.
    pub fn physical_names(&self) -> &[PhysicalName] {
        &self.physical_names
    }

    /// The entities of every dimension, points first.
    pub fn entities(&self) -> &[Entity] {
        &self.entities
    }

    /// Gmsh's node tags, in file order.
    pub fn node_tags(&self) -> &[u64] {
        &self.node_tags
    }

    /// Node coordinates (x, y, z), in file order.
    pub fn coords(&self) -> &[[f64; 3]] {
        &self.coords
    }

    /// The element blocks, in file order.
    pub fn blocks(&self) -> &[ElementBlock] {
        &self.blocks
    }

    /// Number of elements of dimension `dim`.
    pub fn element_count(&self, dim: usize) -> usize {
        self.blocks
            .iter()
            .filter(|b| b.dim == dim)
            .map(ElementBlock::len)
            .sum()
    }

    /// The physical tag of the group `name` of dimension `dim`.
    pub(crate) fn physical_tag(&self, dim: usize, name: &str) -> Option<i32> {
        self.physical_names
            .iter()
            .find(|p| p.dim == dim && p.name == name)
            .map(|p| p.tag)
    }

    /// The element blocks of dimension `dim` on entities of the physical group `tag`.
    pub(crate) fn group_blocks(&self, dim: usize, tag: i32) -> impl Iterator<Item = &ElementBlock> {
        let entities: Vec<i32> = self
            .entities
            .iter()
            .filter(|e| e.dim == dim && e.physical_tags.contains(&tag))
            .map(|e| e.tag)
            .collect();
        self.blocks
            .iter()
            .filter(move |b| b.dim == dim && entities.contains(&b.entity))
    }
}

/// Reads an MSH 4.1 file's bytes; `source` names it in errors.
pub(crate) fn parse(bytes: &[u8], source: &str) -> Result<GmshMesh> {
    let mut c = Cursor::new(source, bytes);
    let encoding = read_format(&mut c)?;
    let mut mesh = GmshMesh {
        source: source.to_string(),
        binary: encoding == Encoding::Binary,
        physical_names: Vec::new(),
        entities: Vec::new(),
        node_tags: Vec::new(),
        coords: Vec::new(),
        blocks: Vec::new(),
    };
    let mut index: Option<TagIndex> = None;
    loop {
        c.skip_blank();
        if c.at_end() {
            return Ok(mesh);
        }
        let (pos, header) = c.line();
        let name = match header {
            [b'$', name @ ..] if !name.starts_with(b"End") => String::from_utf8_lossy(name),
            _ => return Err(c.expected_at(pos, "a section such as `$Nodes`", header)),
        };
        c.set_encoding(encoding);
        match name.as_ref() {
            "MeshFormat" => return Err(c.error_at(pos, "a second `$MeshFormat`")),
            "PhysicalNames" => read_physical_names(&mut c, &mut mesh)?,
            "Entities" => read_entities(&mut c, &mut mesh)?,
            "Nodes" if index.is_some() => return Err(c.error_at(pos, "a second `$Nodes`")),
            "Nodes" => index = Some(read_nodes(&mut c, &mut mesh)?),
            "Elements" => match &index {
                Some(index) => read_elements(&mut c, &mut mesh, index)?,
                None => return Err(c.error_at(pos, "`$Elements` before `$Nodes`")),
            },
            "PartitionedEntities" => {
                return Err(c.error_at(pos, "a partitioned mesh is not read: save it unpartitioned"))
            }
            other => {
                let end = format!("$End{other}");
                if !c.skip_past_line(end.as_bytes()) {
                    return Err(c.error_at(pos, format!("`${other}` has no `{end}`")));
                }
                continue;
            }
        }
        c.expect_line(&format!("$End{name}"))?;
    }
}

/// `$MeshFormat`: version 4.1, ASCII or binary with 8-byte `size_t`, little-endian.
fn read_format(c: &mut Cursor) -> Result<Encoding> {
    c.skip_blank();
    let (pos, header) = c.line();
    if header != b"$MeshFormat" {
        return Err(c.expected_at(pos, "`$MeshFormat` (the start of a Gmsh MSH file)", header));
    }
    let (pos, line) = c.line();
    let words: Vec<&[u8]> = line
        .split(u8::is_ascii_whitespace)
        .filter(|w| !w.is_empty())
        .collect();
    let [version, file_type, data_size] = words[..] else {
        return Err(c.expected_at(pos, "`4.1 0 8` (version, file type, data size)", line));
    };
    if version != VERSION.as_bytes() {
        let found = String::from_utf8_lossy(version);
        return Err(c.error_at(
            pos,
            format!("MSH version {found} is not read, only {VERSION}: {SAVE_AS_41}"),
        ));
    }
    let encoding = match file_type {
        b"0" => Encoding::Ascii,
        b"1" => Encoding::Binary,
        _ => return Err(c.expected_at(pos, "file type 0 (ASCII) or 1 (binary)", file_type)),
    };
    if data_size != b"8" {
        return Err(c.expected_at(pos, "data size 8 (a 64-bit Gmsh)", data_size));
    }
    if encoding == Encoding::Binary {
        c.set_encoding(Encoding::Binary);
        let pos = c.pos();
        if c.int("the binary marker 1")? != 1 {
            return Err(c.error_at(
                pos,
                "a big-endian binary file is not read: save it as ASCII",
            ));
        }
    }
    c.expect_line("$EndMeshFormat")?;
    Ok(encoding)
}

/// `$PhysicalNames` (text in binary files too): dimension, tag and quoted name.
fn read_physical_names(c: &mut Cursor, mesh: &mut GmshMesh) -> Result<()> {
    c.set_encoding(Encoding::Ascii);
    c.begin_record();
    // `0 1 ""`: three numbers' worth of bytes at least.
    let n = c.count("the number of physical names", RecordBytes::of(3, 0, 0))?;
    c.end_record("the number of physical names")?;
    for _ in 0..n {
        c.begin_record();
        let dim = c.int_in("a physical group's dimension", 0, 3)? as usize;
        let tag = c.int("a physical group's tag")?;
        let name = c.quoted("a physical group's name in double quotes")?;
        c.end_record("the name")?;
        mesh.physical_names.push(PhysicalName { dim, tag, name });
    }
    Ok(())
}

/// `$Entities`: points, curves, surfaces and volumes with their physical tags (their
/// coordinates, bounding boxes and bounding entities are skipped).
fn read_entities(c: &mut Cursor, mesh: &mut GmshMesh) -> Result<()> {
    const WHAT: [&str; 4] = ["points", "curves", "surfaces", "volumes"];
    // A point: tag, x, y, z, number of physical tags; a curve, surface or volume: tag,
    // bounding box, numbers of physical tags and of bounding entities.
    let each = |dim| match dim {
        0 => RecordBytes::of(1, 1, 3),
        _ => RecordBytes::of(1, 2, 6),
    };
    c.begin_record();
    let mut counts = [0; 4];
    for (dim, count) in counts.iter_mut().enumerate() {
        *count = c.count(format_args!("the number of {}", WHAT[dim]), each(dim))?;
    }
    c.end_record("the numbers of entities")?;
    let tag_bytes = RecordBytes::of(1, 0, 0);
    for (dim, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            c.begin_record();
            let tag = c.int(format_args!("the tag of one of the {}", WHAT[dim]))?;
            let coordinates = if dim == 0 { 3 } else { 6 };
            for _ in 0..coordinates {
                c.float(format_args!("a coordinate of entity {tag}"))?;
            }
            let n = c.count(
                format_args!("entity {tag}'s number of physical tags"),
                tag_bytes,
            )?;
            let physical_tags = (0..n)
                .map(|_| c.int(format_args!("a physical tag of entity {tag}")))
                .collect::<Result<Vec<_>>>()?;
            if dim > 0 {
                let n = c.count(
                    format_args!("entity {tag}'s number of bounding entities"),
                    tag_bytes,
                )?;
                for _ in 0..n {
                    c.int(format_args!("a bounding entity of entity {tag}"))?;
                }
            }
            c.end_record(format_args!("entity {tag}"))?;
            mesh.entities.push(Entity {
                dim,
                tag,
                physical_tags,
            });
        }
    }
    Ok(())
}

/// `$Nodes`: blocks of tags then coordinates (parametric coordinates skipped); tags are
/// checked unique and within the header's range.
fn read_nodes(c: &mut Cursor, mesh: &mut GmshMesh) -> Result<TagIndex> {
    let node_bytes = RecordBytes::of(0, 1, 3);
    c.begin_record();
    let header = c.pos();
    let blocks = c.count("the number of node blocks", RecordBytes::of(3, 1, 0))?;
    let total = c.count("the number of nodes", node_bytes)?;
    let (min, max) = (
        c.size("the smallest node tag")?,
        c.size("the largest node tag")?,
    );
    c.end_record("the largest node tag")?;
    let mut index = TagIndex::new(min, max, total);
    mesh.node_tags.reserve_exact(total);
    mesh.coords.reserve_exact(total);
    for _ in 0..blocks {
        c.begin_record();
        let dim = c.int_in("a node block's entity dimension", 0, 3)? as usize;
        c.int("a node block's entity tag")?;
        let parametric = c.int_in("a node block's parametric flag", 0, 1)? as usize;
        let pos = c.pos();
        let n = c.count("a node block's number of nodes", node_bytes)?;
        c.end_record("the number of nodes")?;
        if mesh.node_tags.len() + n > total {
            return Err(c.error_at(
                pos,
                format!("the blocks hold more nodes than the {total} of the header"),
            ));
        }
        for _ in 0..n {
            c.begin_record();
            let pos = c.pos();
            let tag = c.size("a node tag")?;
            index
                .insert(tag, mesh.node_tags.len())
                .map_err(|e| c.error_at(pos, e))?;
            c.end_record("a node tag")?;
            mesh.node_tags.push(tag);
        }
        for k in 0..n {
            c.begin_record();
            let tag = mesh.node_tags[mesh.node_tags.len() - n + k];
            let mut x = [0.0; 3];
            for (axis, v) in x.iter_mut().enumerate() {
                *v = c.float(format_args!("coordinate {} of node {tag}", axis + 1))?;
            }
            for _ in 0..parametric * dim {
                c.float(format_args!("a parametric coordinate of node {tag}"))?;
            }
            c.end_record(format_args!("the coordinates of node {tag}"))?;
            mesh.coords.push(x);
        }
    }
    if mesh.node_tags.len() != total {
        let held = mesh.node_tags.len();
        return Err(c.error_at(
            header,
            format!("the header states {total} nodes, its blocks hold {held}"),
        ));
    }
    Ok(index)
}

/// `$Elements`: blocks of one type on one entity; node tags resolved through `index`.
fn read_elements(c: &mut Cursor, mesh: &mut GmshMesh, index: &TagIndex) -> Result<()> {
    c.begin_record();
    let header = c.pos();
    let blocks = c.count("the number of element blocks", RecordBytes::of(3, 1, 0))?;
    let total = c.count("the number of elements", RecordBytes::of(0, 2, 0))?;
    c.size("the smallest element tag")?;
    c.size("the largest element tag")?;
    c.end_record("the largest element tag")?;
    let mut held = 0;
    for _ in 0..blocks {
        let block = read_element_block(c, index)?;
        held += block.len();
        mesh.blocks.push(block);
    }
    if held != total {
        return Err(c.error_at(
            header,
            format!("the header states {total} elements, its blocks hold {held}"),
        ));
    }
    Ok(())
}

/// One block of `$Elements`.
fn read_element_block(c: &mut Cursor, index: &TagIndex) -> Result<ElementBlock> {
    c.begin_record();
    let dim = c.int_in("an element block's entity dimension", 0, 3)? as usize;
    let entity = c.int("an element block's entity tag")?;
    let pos = c.pos();
    let number = c.int("an element type")?;
    let element_type = ElementType::from_number(number).ok_or_else(|| {
        c.error_at(
            pos,
            format!("element type {number} is not one of Gmsh's with a fixed number of nodes"),
        )
    })?;
    if element_type.dim != dim {
        return Err(c.error_at(
            pos,
            format!(
                "element {element_type} is {}-D, on an entity of dimension {dim}",
                element_type.dim
            ),
        ));
    }
    let each = RecordBytes::of(0, 1 + element_type.nodes, 0);
    let n = c.count("an element block's number of elements", each)?;
    c.end_record("the number of elements")?;
    let mut tags = Vec::with_capacity(n);
    let mut nodes = Vec::with_capacity(n * element_type.nodes);
    for _ in 0..n {
        c.begin_record();
        let tag = c.size("an element tag")?;
        for k in 0..element_type.nodes {
            let pos = c.pos();
            let node = c.size(format_args!(
                "node {} of element {tag} ({element_type})",
                k + 1
            ))?;
            let i = index.get(node).ok_or_else(|| {
                c.error_at(
                    pos,
                    format!("element {tag} refers to node {node}, which `$Nodes` does not define"),
                )
            })?;
            nodes.push(i);
        }
        c.end_record(format_args!(
            "the {} nodes of element {tag} ({element_type})",
            element_type.nodes
        ))?;
        tags.push(tag);
    }
    Ok(ElementBlock {
        dim,
        entity,
        element_type,
        tags,
        nodes,
    })
}

/// Node tag → index into the file's nodes: a table over the header's tag range when it is
/// compact, else a hash map (sparse tags).
enum TagIndex {
    Dense {
        first: u64,
        slots: Vec<usize>,
    },
    Sparse {
        range: (u64, u64),
        map: HashMap<u64, usize>,
    },
}

impl TagIndex {
    /// An empty index for `count` tags in `min ..= max`.
    fn new(min: u64, max: u64, count: usize) -> Self {
        let span = max
            .checked_sub(min)
            .and_then(|s| s.checked_add(1))
            .unwrap_or(0);
        if count > 0 && span <= DENSE_SPAN_FACTOR * count as u64 + DENSE_SPAN_EXTRA {
            Self::Dense {
                first: min,
                slots: vec![usize::MAX; span as usize],
            }
        } else {
            Self::Sparse {
                range: (min, max),
                map: HashMap::with_capacity(count),
            }
        }
    }

    /// Records node `tag` at `index`; a message when it is outside the range or a repeat.
    fn insert(&mut self, tag: u64, index: usize) -> std::result::Result<(), String> {
        let (min, max) = self.range();
        if !(min..=max).contains(&tag) {
            return Err(format!(
                "node tag {tag} is outside the range {min} ..= {max} of the header"
            ));
        }
        let previous = match self {
            Self::Dense { first, slots } => {
                let slot = &mut slots[(tag - *first) as usize];
                std::mem::replace(slot, index)
            }
            Self::Sparse { map, .. } => map.insert(tag, index).unwrap_or(usize::MAX),
        };
        if previous == usize::MAX {
            Ok(())
        } else {
            Err(format!("node tag {tag} appears twice"))
        }
    }

    /// The tag range of the header.
    fn range(&self) -> (u64, u64) {
        match self {
            Self::Dense { first, slots } => (*first, *first + slots.len() as u64 - 1),
            Self::Sparse { range, .. } => *range,
        }
    }

    /// The index of node `tag`.
    fn get(&self, tag: u64) -> Option<usize> {
        match self {
            Self::Dense { first, slots } => tag
                .checked_sub(*first)
                .and_then(|k| slots.get(usize::try_from(k).ok()?))
                .copied()
                .filter(|&i| i != usize::MAX),
            Self::Sparse { map, .. } => map.get(&tag).copied(),
        }
    }
}
