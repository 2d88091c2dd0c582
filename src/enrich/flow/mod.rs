//! Numeric core of the `flow` chart kind: 2-D vector fields and the curves and images drawn from
//! them.
//!
//! - [`field`]: [`field::VectorField`], a bilinear vector field on a rectilinear grid, optionally
//!   unsteady (linear in time), with its exact cell Jacobian.
//! - [`integrate`]: one step of Euler, midpoint (RK2), classical RK4 or adaptive Dormand–Prince
//!   5(4), on the direction field or the true velocity.
//! - [`streamline`]: streamlines and pathlines traced from a seed, with the reason they stopped.
//! - [`seeding`]: seeds on rakes, grids and circles, and evenly spaced streamlines
//!   (Jobard & Lefer 1997).
//! - [`lic`]: line integral convolution of white noise (Cabral & Leedom 1993), in parallel by rows.
//! - [`budget`]: the total steps and seeding attempts one chart may spend.
//! - [`topology`]: critical points of the bilinear interpolant classified by their Jacobian,
//!   saddle separatrices and boundary switch points (Helman & Hesselink 1989).
//!
//! Everything here is a pure function of its input (and seed): no drawing, no I/O.

pub mod budget;
pub mod field;
pub mod integrate;
pub mod lic;
pub mod seeding;
pub mod streamline;
pub mod topology;
