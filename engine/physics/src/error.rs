//! Why collision geometry could not be built.

use std::fmt;

/// A level's triangles could not be turned into collision geometry. Each variant names the
/// mesh (when the triangles came from a [`scene::Scene`]) and the offending element.
#[derive(Clone, Debug, PartialEq)]
pub enum CollisionError {
    /// There is nothing to collide with: no triangles at all, or only degenerate ones.
    NoTriangles,
    /// A vertex position is NaN or infinite.
    NonFinitePosition { mesh: Option<String>, vertex: usize },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange { mesh: Option<String>, triangle: usize, index: u32, vertex_count: usize },
    /// A mesh's index list is not a whole number of triangles.
    PartialTriangle { mesh: String, index_count: usize },
    /// The meshes together have more vertices than a `u32` index can address.
    TooManyVertices { count: usize },
    /// rapier refused the triangle mesh (not expected after the checks above).
    Rejected(String),
}

/// `mesh "name": ` or nothing, to prefix a message.
struct MeshPrefix<'a>(Option<&'a str>);

impl fmt::Display for MeshPrefix<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(name) => write!(f, "mesh {name:?}: "),
            None => Ok(()),
        }
    }
}

impl fmt::Display for CollisionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoTriangles => write!(f, "no collision geometry: the level has no non-degenerate triangle"),
            Self::NonFinitePosition { mesh, vertex } => {
                write!(f, "{}vertex {vertex} has a NaN or infinite position", MeshPrefix(mesh.as_deref()))
            }
            Self::IndexOutOfRange { mesh, triangle, index, vertex_count } => write!(
                f,
                "{}triangle {triangle} uses vertex {index}, but there are only {vertex_count} vertices",
                MeshPrefix(mesh.as_deref())
            ),
            Self::PartialTriangle { mesh, index_count } => {
                write!(f, "mesh {mesh:?}: {index_count} indices is not a whole number of triangles")
            }
            Self::TooManyVertices { count } => {
                write!(f, "{count} vertices in all, more than a 32-bit index can address")
            }
            Self::Rejected(why) => write!(f, "the collision mesh was rejected: {why}"),
        }
    }
}

impl std::error::Error for CollisionError {}
