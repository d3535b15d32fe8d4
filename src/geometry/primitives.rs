//! The scene's primitives as one numbered list, stored in two ways: shapes kept whole as
//! [`Primitive`] records, and the triangles of large meshes kept as runs over the mesh's faces,
//! made from the mesh when asked for. A triangle record copies its three corners next to its
//! mesh, face and material (52 bytes); a run costs a few bytes for the whole mesh, so a mesh of a
//! million faces does not need 52 MB beside its vertex buffers and the accelerator.
//!
//! Numbers follow the file: a shape's primitives are numbered after those of the shapes before
//! it, whichever way they are stored, so ties broken by number (the accelerators' and the
//! emitters') do not depend on the storage. Meshes of at most [`RECORD_MESH_MAX_FACES`] faces
//! (quads, boxes, models of up to tens of thousands of faces) keep their records: they cost little
//! memory, and gathering an area light's beam candidates and shading a hit read a record without
//! a lookup.

use std::borrow::Cow;
use std::ops::Range;

use super::{Mesh, Primitive, Shape, Triangle};
use crate::accel::aabb::Aabb;

/// Meshes of at most this many faces keep one [`Primitive`] record per triangle; larger ones are
/// stored as a run over their faces. At this size the records of one mesh are 3.4 MB, beside a
/// tree of about as much.
pub const RECORD_MESH_MAX_FACES: usize = 1 << 16;

/// Every primitive of a scene, numbered from 0 in file order, with the meshes their triangles
/// belong to.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Primitives {
    records: Vec<Primitive>,
    /// Consecutive numbers stored one way, in order of their first number; empty while every
    /// primitive is a record (numbers are then indices into `records`).
    runs: Vec<Run>,
    meshes: Vec<Mesh>,
    len: usize,
}

/// Primitives `start..` up to the next run's start (or the end).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Run {
    start: usize,
    source: Source,
}

/// Where a primitive is stored.
enum Slot<'a> {
    Record(&'a Primitive),
    /// Face `face` of mesh `mesh`, of material `material`.
    Face {
        mesh: u32,
        face: u32,
        material: u32,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    /// Records from index `first` on.
    Records { first: usize },
    /// Every face of a mesh, in order, all of one material.
    Faces { mesh: u32, material: u32 },
}

impl From<Vec<Primitive>> for Primitives {
    /// Primitives that are all records, with no meshes (a triangle's `mesh` then names none:
    /// its hit record cannot be asked for).
    fn from(records: Vec<Primitive>) -> Primitives {
        Primitives::from_records(records, Vec::new())
    }
}

impl Primitives {
    /// Primitives that are all records, whose triangles belong to `meshes`.
    pub fn from_records(records: Vec<Primitive>, meshes: Vec<Mesh>) -> Primitives {
        Primitives {
            len: records.len(),
            records,
            runs: Vec::new(),
            meshes,
        }
    }

    /// Number of primitives.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The meshes, indexed by a triangle's `mesh`.
    #[inline]
    pub fn meshes(&self) -> &[Mesh] {
        &self.meshes
    }

    /// Appends a shape as a record.
    pub fn push(&mut self, primitive: Primitive) {
        if matches!(
            self.runs.last(),
            Some(Run {
                source: Source::Faces { .. },
                ..
            })
        ) {
            let first = self.records.len();
            self.runs.push(Run {
                start: self.len,
                source: Source::Records { first },
            });
        }
        self.records.push(primitive);
        self.len += 1;
    }

    /// Appends every face of `mesh` as a triangle of `material`, face order kept: as records
    /// for a mesh of at most [`RECORD_MESH_MAX_FACES`] faces, else as one run.
    pub fn push_mesh(&mut self, mesh: Mesh, material: u32) {
        if mesh.faces.len() > RECORD_MESH_MAX_FACES {
            return self.push_faces(mesh, material);
        }
        let index = self.meshes.len() as u32;
        for face in 0..mesh.faces.len() as u32 {
            self.push(Primitive {
                shape: Shape::Triangle(triangle(&mesh, index, face)),
                material,
            });
        }
        self.meshes.push(mesh);
    }

    /// Appends every face of `mesh` as a triangle of `material`, face order kept, as one run
    /// whatever its size: what [`Primitives::push_mesh`] does for a large mesh.
    pub fn push_faces(&mut self, mesh: Mesh, material: u32) {
        if self.runs.is_empty() && !self.records.is_empty() {
            self.runs.push(Run {
                start: 0,
                source: Source::Records { first: 0 },
            });
        }
        self.runs.push(Run {
            start: self.len,
            source: Source::Faces {
                mesh: self.meshes.len() as u32,
                material,
            },
        });
        self.len += mesh.faces.len();
        self.meshes.push(mesh);
    }

    /// Where primitive `i` is stored: the fast path for a list of records only is inlined, the
    /// lookup through runs kept out of line so that the callers' tests stay small.
    #[inline(always)]
    fn slot(&self, i: u32) -> Slot<'_> {
        match self.runs.is_empty() {
            true => Slot::Record(&self.records[i as usize]),
            false => self.slot_in_runs(i as usize),
        }
    }

    /// [`Primitives::slot`] where there are runs: the run holding `i`, found by bisection.
    #[inline(never)]
    fn slot_in_runs(&self, i: usize) -> Slot<'_> {
        assert!(i < self.len, "primitive {i} is past the end ({})", self.len);
        let run = self.runs[self.runs.partition_point(|r| r.start <= i) - 1];
        let k = i - run.start;
        match run.source {
            Source::Records { first } => Slot::Record(&self.records[first + k]),
            Source::Faces { mesh, material } => Slot::Face {
                mesh,
                face: k as u32,
                material,
            },
        }
    }

    /// Primitive `i` (a triangle of a run is made from its mesh). Panics if `i ≥ len()`.
    #[inline(always)]
    pub fn get(&self, i: u32) -> Primitive {
        match self.slot(i) {
            Slot::Record(r) => *r,
            Slot::Face {
                mesh,
                face,
                material,
            } => Primitive {
                shape: self.face(mesh, face),
                material,
            },
        }
    }

    /// The shape of primitive `i`: borrowed from its record, or made from its mesh. What the
    /// intersection tests read, without copying a record.
    #[inline(always)]
    pub fn shape(&self, i: u32) -> Cow<'_, Shape> {
        match self.slot(i) {
            Slot::Record(r) => Cow::Borrowed(&r.shape),
            Slot::Face { mesh, face, .. } => Cow::Owned(self.face(mesh, face)),
        }
    }

    /// The material of primitive `i`, without making its shape.
    #[inline(always)]
    pub fn material(&self, i: u32) -> u32 {
        match self.slot(i) {
            Slot::Record(r) => r.material,
            Slot::Face { material, .. } => material,
        }
    }

    /// The record of primitive `i`, or `None` for a triangle of a run (made from its mesh).
    #[inline]
    pub fn record(&self, i: u32) -> Option<&Primitive> {
        match self.slot(i) {
            Slot::Record(r) => Some(r),
            Slot::Face { .. } => None,
        }
    }

    /// Face `face` of mesh `mesh` as a triangle shape.
    #[inline]
    fn face(&self, mesh: u32, face: u32) -> Shape {
        Shape::Triangle(triangle(&self.meshes[mesh as usize], mesh, face))
    }

    /// The runs with their extents, `(start, count, source)` in order; one run of records when
    /// there are no runs.
    fn spans(&self) -> impl Iterator<Item = (usize, usize, Source)> + '_ {
        let whole = self
            .runs
            .is_empty()
            .then_some((0, self.len, Source::Records { first: 0 }));
        let runs = self.runs.iter().enumerate().map(|(k, r)| {
            let end = self.runs.get(k + 1).map_or(self.len, |next| next.start);
            (r.start, end - r.start, r.source)
        });
        whole.into_iter().chain(runs)
    }

    /// Every primitive, in order.
    pub fn iter(&self) -> impl Iterator<Item = Primitive> + '_ {
        (0..self.len as u32).map(|i| self.get(i))
    }

    /// Calls `f` with every primitive's shape, in order, walking the records and runs in turn:
    /// no lookup per primitive and no record copied.
    pub fn for_each_shape(&self, mut f: impl FnMut(&Shape)) {
        for (_, count, source) in self.spans() {
            match source {
                Source::Records { first } => {
                    self.records[first..first + count]
                        .iter()
                        .for_each(|r| f(&r.shape));
                }
                Source::Faces { mesh, .. } => {
                    (0..count as u32).for_each(|face| f(&self.face(mesh, face)));
                }
            }
        }
    }

    /// How many of the primitives are triangles (every face of a mesh stored as a run is one).
    pub fn triangle_count(&self) -> usize {
        self.spans()
            .map(|(_, count, source)| match source {
                Source::Records { first } => self.records[first..first + count]
                    .iter()
                    .filter(|r| matches!(r.shape, Shape::Triangle(_)))
                    .count(),
                Source::Faces { .. } => count,
            })
            .sum()
    }

    /// The box of every bounded shape ([`Aabb::EMPTY`] where there is none).
    pub fn bounds(&self) -> Aabb {
        let mut bounds = Aabb::EMPTY;
        self.for_each_shape(|s| {
            if s.is_bounded() {
                bounds = bounds.union(s.bounds());
            }
        });
        bounds
    }

    /// The primitives stored as records, with their numbers, in order: every shape but the
    /// triangles of large meshes (so every sphere, cylinder and plane).
    pub fn records(&self) -> impl Iterator<Item = (u32, &Primitive)> + '_ {
        self.spans().flat_map(|(start, count, source)| {
            let records = match source {
                Source::Records { first } => &self.records[first..first + count],
                Source::Faces { .. } => &[],
            };
            (start as u32..).zip(records)
        })
    }

    /// The numbers of the unbounded primitives (planes, all records), in order.
    pub fn unbounded(&self) -> Vec<u32> {
        self.records()
            .filter(|(_, p)| !p.shape.is_bounded())
            .map(|(i, _)| i)
            .collect()
    }

    /// The primitives numbered `range`.
    pub fn range(&self, range: Range<u32>) -> Vec<Primitive> {
        range.map(|i| self.get(i)).collect()
    }

    /// Bytes of the records and runs: what the list costs beside its meshes.
    pub fn record_bytes(&self) -> usize {
        self.records.len() * std::mem::size_of::<Primitive>()
            + self.runs.len() * std::mem::size_of::<Run>()
    }

    /// Bytes of the meshes' buffers: positions, normals, texture coordinates and faces.
    pub fn mesh_bytes(&self) -> usize {
        self.meshes.iter().map(Mesh::bytes).sum()
    }
}

/// Face `face` of `mesh` (number `index`) as a triangle, its corners copied from the mesh.
#[inline]
fn triangle(mesh: &Mesh, index: u32, face: u32) -> Triangle {
    let [a, b, c] = mesh.faces[face as usize];
    let at = |v: u32| mesh.positions[v as usize];
    Triangle {
        p: [at(a), at(b), at(c)],
        mesh: index,
        face,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{MeshUv, Plane, Sphere};
    use crate::math::Vec3;

    fn sphere(x: f32, material: u32) -> Primitive {
        Primitive {
            shape: Shape::Sphere(Sphere::new(Vec3::new(x, 0.0, 0.0), 1.0, Vec3::Y, Vec3::X)),
            material,
        }
    }

    /// A strip of `n` faces over `n + 2` vertices.
    fn strip(n: usize, y: f32) -> Mesh {
        Mesh {
            positions: (0..n + 2)
                .map(|v| Vec3::new(v as f32, y, (v % 2) as f32))
                .collect(),
            normals: None,
            uv: MeshUv::Strip,
            faces: (0..n as u32).map(|f| [f, f + 1, f + 2]).collect(),
        }
    }

    /// The reference storage: a record per primitive, triangles with their corners copied.
    fn records_of(parts: &[Result<Primitive, (Mesh, u32)>]) -> Vec<Primitive> {
        let mut out = Vec::new();
        let mut meshes = 0;
        for part in parts {
            match part {
                Ok(p) => out.push(*p),
                Err((m, material)) => {
                    for f in 0..m.faces.len() as u32 {
                        out.push(Primitive {
                            shape: Shape::Triangle(triangle(m, meshes, f)),
                            material: *material,
                        });
                    }
                    meshes += 1;
                }
            }
        }
        out
    }

    #[test]
    fn every_number_names_the_primitive_a_list_of_records_would() {
        let big = RECORD_MESH_MAX_FACES + 1;
        let cases: Vec<Vec<Result<Primitive, (Mesh, u32)>>> = vec![
            vec![],
            vec![Ok(sphere(0.0, 0)), Ok(sphere(1.0, 1))],
            vec![Err((strip(big, 0.0), 2))],
            vec![Err((strip(3, 0.0), 1)), Ok(sphere(0.0, 0))],
            vec![
                Ok(sphere(0.0, 0)),
                Err((strip(big, 1.0), 3)),
                Ok(sphere(2.0, 1)),
                Err((strip(5, 2.0), 4)),
                Err((strip(big + 7, 3.0), 5)),
                Err((strip(big, 4.0), 6)),
                Ok(Primitive {
                    shape: Shape::Plane(Plane::new(Vec3::Y, -1.0)),
                    material: 7,
                }),
                Ok(sphere(3.0, 2)),
            ],
        ];
        for parts in cases {
            let mut prims = Primitives::default();
            for part in &parts {
                match part {
                    Ok(p) => prims.push(*p),
                    Err((m, material)) => prims.push_mesh(m.clone(), *material),
                }
            }
            let want = records_of(&parts);
            assert_eq!(prims.len(), want.len());
            assert_eq!(prims.is_empty(), want.is_empty());
            for (i, w) in want.iter().enumerate() {
                assert_eq!(prims.get(i as u32), *w, "primitive {i}");
                assert_eq!(prims.material(i as u32), w.material, "primitive {i}");
                assert_eq!(*prims.shape(i as u32), w.shape, "primitive {i}");
                if let Some(r) = prims.record(i as u32) {
                    assert_eq!(r, w, "primitive {i}");
                }
            }
            assert_eq!(prims.iter().collect::<Vec<_>>(), want);
            let mut shapes = Vec::new();
            prims.for_each_shape(|s| shapes.push(*s));
            assert!(shapes.iter().eq(want.iter().map(|w| &w.shape)));
            let records: Vec<(u32, Primitive)> = prims.records().map(|(i, p)| (i, *p)).collect();
            let (mut number, mut want_records) = (0, Vec::new());
            for part in &parts {
                let (count, recorded) = match part {
                    Ok(_) => (1, true),
                    Err((m, _)) => (m.faces.len(), m.faces.len() <= RECORD_MESH_MAX_FACES),
                };
                if recorded {
                    want_records.extend((number..number + count).map(|i| (i as u32, want[i])));
                }
                number += count;
            }
            assert_eq!(records, want_records);
            let recorded = (0..want.len() as u32).filter(|&i| prims.record(i).is_some());
            assert!(recorded.eq(want_records.iter().map(|r| r.0)));
            let unbounded: Vec<u32> = (0..want.len() as u32)
                .filter(|&i| !want[i as usize].shape.is_bounded())
                .collect();
            assert_eq!(prims.unbounded(), unbounded);
            let n = want.len() as u32;
            assert_eq!(prims.range(n / 3..n), want[n as usize / 3..]);
            let meshes = parts.iter().filter(|p| p.is_err()).count();
            assert_eq!(prims.meshes().len(), meshes);
        }
    }

    #[test]
    fn a_large_mesh_costs_a_run_not_a_record_per_face() {
        let mut prims = Primitives::default();
        prims.push(sphere(0.0, 0));
        let before = prims.record_bytes();
        prims.push_mesh(strip(100_000, 0.0), 1);
        assert_eq!(prims.len(), 100_001);
        assert!(prims.record_bytes() - before <= 2 * std::mem::size_of::<Run>());
        let mut small = Primitives::default();
        small.push_mesh(strip(RECORD_MESH_MAX_FACES, 0.0), 0);
        assert_eq!(
            small.record_bytes(),
            RECORD_MESH_MAX_FACES * std::mem::size_of::<Primitive>()
        );
    }

    #[test]
    #[should_panic(expected = "past the end")]
    fn a_number_past_the_end_is_refused() {
        let mut prims = Primitives::default();
        prims.push(sphere(0.0, 0));
        prims.push_mesh(strip(RECORD_MESH_MAX_FACES + 1, 0.0), 0);
        let _ = prims.get(RECORD_MESH_MAX_FACES as u32 + 2);
    }
}
