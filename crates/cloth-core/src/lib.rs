//! cloth-core: the cloth model and its solver.
//!
//! Fabric is a particle system on a triangle mesh with material (warp, weft)
//! coordinates. Stretch, shear and bending energies give forces and Jacobians;
//! explicit, symplectic and linearised implicit Euler integrate them, the
//! implicit one through a filtered block-sparse PCG (Baraff & Witkin 1998,
//! Ascher & Boxerman 2003). No file formats, no collision library, no I/O.

// `!(x > 0.0)` is how NaN is refused along with the out-of-range values; indexed loops
// read better than iterator chains in the small dense element algebra.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]

// Bottom-up: each module uses only those above it.
pub mod math;
pub mod parallelism;
mod spatial;
pub mod error;
pub mod mesh;
pub mod fabric;
pub mod energy;
pub mod metrics;
pub mod linalg;
mod forces;
pub mod contact;
pub mod self_contact;
pub mod solver;

pub use contact::{
    body_intersections_by_edge, count_body_intersections, BodyIntersections, Collider, ContactMode,
    ParticlePath, PassThrough, Proximity, SharpFeature, SurfacePoint,
};
pub use energy::attachment::Attachment;
pub use error::ParamError;
pub use fabric::{
    BendingLaw, BendingRigidity, Fabric, KesConversion, KesDirection, KesMeasurement, SourceCoefficients,
    TensileLaw, UnusedKes,
};
pub use mesh::{
    components, within_rings, ClothMesh, GridBuilder, GridDiagonals, GridShape, MeshError, Neighbours,
};
pub use metrics::{GridStretch, StrainReport};
pub use self_contact::{
    closest_self_approach, count_self_intersections, self_intersecting_pairs, Intersections, LayerPass,
    LayerPassing, SelfCollision, SelfCrossings, Tangle,
};
pub use solver::{
    Constraint, ConstraintKind, DivergenceReason, Integrator, Interrupt, PcgSettings, Pin, PinMotion,
    RestCriteria, RestOutcome, SeamPull, SimError, Simulation, SimulationBuilder, SolveFailure,
    SolverSettings, StepStats, StopReason,
};
