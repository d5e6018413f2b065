//! Typed errors. Every one is raised before the first row leaves the renderer, so a failed
//! frame never leaves a half-drawn picture behind.

/// A table whose capacity a scene can exceed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Table {
    /// The polygon table (polygons that survive culling and touch the screen).
    Polygons,
    /// The edge table (edges that cross a sample row on screen).
    Edges,
    /// The vertex pool (the scan-line method: the vertices of every polygon drawn, after
    /// clipping).
    Vertices,
    /// The active list (polygons spanning one row; twice as many active edges).
    ActivePolygons,
    /// The row buffers (`depth[x]`, `intensity[x]`): the frame is wider than they are.
    RowWidth,
    /// A whole-frame or band buffer (z-buffer rows, tiled z-buffer band): the frame is
    /// taller or wider than it holds.
    FrameBuffer,
    /// Pieces (polygons and the parts splitting made of them): depth-sort and BSP.
    Pieces,
    /// BSP tree depth (the build's explicit stack).
    BspDepth,
    /// Warnock's potentially-visible lists, summed over the levels of subdivision.
    VisibleList,
    /// Translucent fragments in one row (A-buffer).
    Fragments,
}

/// What went wrong, and what to do about it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// The scene needs more room in `table` than the renderer has: build it with a capacity of
    /// at least `needed` (see [`crate::requirements()`]).
    Capacity {
        /// Which table.
        table: Table,
        /// What this scene needs.
        needed: u32,
        /// What the renderer has.
        capacity: u32,
    },
    /// Face `face` refers to vertex `index`, which the mesh does not have: fix the face list.
    IndexOutOfRange {
        /// Face number in the scene (objects in order, faces in order).
        face: u32,
        /// The offending index.
        index: u32,
    },
    /// Face `face` has fewer than 3 vertices: drop it or complete it.
    TooFewVertices {
        /// Face number.
        face: u32,
    },
    /// Face `face` has more than [`crate::raster::MAX_FACE_VERTICES`] vertices: split it.
    TooManyVertices {
        /// Face number.
        face: u32,
    },
    /// A vertex of face `face` is NaN, infinite or outside the number format's range (or a
    /// transform pushed it there): fix the data or scale the model down.
    NonFinite {
        /// Face number.
        face: u32,
    },
    /// Face `face` is not convex (its outline goes down and up more than once, or clipping it
    /// made more corners than a convex face can have): split it into triangles.
    NotConvex {
        /// Face number.
        face: u32,
    },
    /// A mesh has `normals` precomputed normals for its `faces` faces: give exactly one per
    /// face, or none (then model mode computes them).
    Normals {
        /// Faces in the mesh.
        faces: u32,
        /// Normals in the mesh.
        normals: u32,
    },
    /// The configuration is impossible: size 0 or above `MAX_VIEWPORT`, sub-pixel bits
    /// outside 1..=8, or depth-cue parameters that are not finite, not `near < far`, or a
    /// `floor` outside 0..=1.
    BadConfig,
    /// This method does not implement `feature`: pick a method that does (the message says
    /// which) or another setting.
    Unsupported {
        /// What is not supported, and where it is.
        feature: &'static str,
    },
}

impl core::fmt::Display for Table {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Table::Polygons => "polygon table",
            Table::Edges => "edge table",
            Table::Vertices => "vertex pool",
            Table::ActivePolygons => "active list",
            Table::RowWidth => "row buffer",
            Table::FrameBuffer => "frame buffer",
            Table::Pieces => "piece table",
            Table::BspDepth => "BSP stack",
            Table::VisibleList => "potentially-visible list",
            Table::Fragments => "fragment list",
        })
    }
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Error::Capacity {
                table,
                needed,
                capacity,
            } => write!(
                f,
                "{table} holds {capacity} but this scene needs {needed}: raise that capacity"
            ),
            Error::IndexOutOfRange { face, index } => {
                write!(f, "face {face}: vertex index {index} out of range")
            }
            Error::TooFewVertices { face } => write!(f, "face {face}: fewer than 3 vertices"),
            Error::TooManyVertices { face } => write!(
                f,
                "face {face}: more than {} vertices",
                crate::raster::MAX_FACE_VERTICES
            ),
            Error::NonFinite { face } => write!(
                f,
                "face {face}: coordinate not finite or outside the number format"
            ),
            Error::NotConvex { face } => write!(f, "face {face}: not convex"),
            Error::Normals { faces, normals } => write!(
                f,
                "mesh has {normals} normals for {faces} faces: give one per face or none"
            ),
            Error::BadConfig => write!(
                f,
                "bad configuration: size must be 1..=2048, sub-pixel bits 1..=8, depth cue near < far with floor 0..=1"
            ),
            Error::Unsupported { feature } => write!(f, "not supported by this method: {feature}"),
        }
    }
}

/// A render that failed: either the scene (before any row was sent) or the sink.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderError<E> {
    /// The scene or configuration was rejected; no row was sent.
    Scene(Error),
    /// The sink failed while rows were being sent.
    Sink(E),
}

impl<E> From<Error> for RenderError<E> {
    fn from(e: Error) -> Self {
        RenderError::Scene(e)
    }
}
