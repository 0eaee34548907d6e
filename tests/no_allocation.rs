//! After its first step a simulation allocates nothing on the heap (the first step is
//! where faer's matrix kernels size their thread-local buffers, once per thread). In
//! parallel the step enters rayon's pool once, and rayon's global injector allocates a
//! small block every 63 entries: at most one allocation per 63 steps, none of ours.

use cloth::{Fabric, GridBuilder, Integrator, Pin, SimulationBuilder, SolverSettings};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn steps_do_not_allocate_alone_or_with_layers_in_contact() {
    for parallel in [false, true] {
        for integrator in [
            Integrator::ImplicitEuler,
            Integrator::ExplicitEuler,
            Integrator::SymplecticEuler,
        ] {
            let mesh = GridBuilder::new(20, 20).size(0.5, 0.5).build().unwrap();
            let g = mesh.grid().unwrap();
            // Forward Euler with Rayleigh damping is stable for h < 2 / (beta omega_max^2), ~1e-5 s here.
            let h = if integrator == Integrator::ImplicitEuler {
                1.0 / 60.0
            } else {
                5e-6
            };
            let settings = SolverSettings {
                integrator,
                time_step: h,
                parallel,
                ..Default::default()
            };
            let mut sim =
                SimulationBuilder::new(mesh, Fabric::cotton_like().with_damping(1e-3).with_drag(0.1))
                    .settings(settings)
                    .pin(Pin::fixed(g.index(0, 19)))
                    .pin(Pin::path(g.index(19, 19), |t| {
                        cloth::math::Vec3::new(0.5, 0.5 + 0.01 * t, 0.0)
                    }))
                    .build()
                    .unwrap();
            sim.step().unwrap();
            let before = ALLOCATIONS.load(Ordering::Relaxed);
            let steps = 126;
            for _ in 0..steps {
                sim.step().unwrap();
            }
            let count = ALLOCATIONS.load(Ordering::Relaxed) - before;
            let allowed = if parallel { steps / 63 + 1 } else { 0 };
            println!("{integrator:?}, parallel {parallel}: {count} allocations in {steps} steps");
            assert!(
                count <= allowed,
                "{integrator:?} (parallel {parallel}) allocated {count} times in {steps} steps"
            );
        }
    }
    steps_with_layers_in_contact_do_not_allocate();
}

/// The stacked sheets' steps once their contacts have formed: the search, the couplings,
/// friction's second solve and the impact passes reuse their buffers. The lists of
/// contacts and impacts have no size known in advance: they double when a step finds more
/// than any step before, a handful of times in a run, never once a step. (Run from the
/// test above: tests on parallel threads would count each other's allocations.)
fn steps_with_layers_in_contact_do_not_allocate() {
    let mut scene = cloth_fixtures::StackedSheets {
        particles_per_side: 15,
        ..Default::default()
    }
    .build()
    .unwrap();
    let sim = &mut scene.simulation;
    let settings = SolverSettings {
        parallel: false,
        ..sim.settings().clone()
    };
    sim.set_settings(settings).unwrap();
    // Until the layers have met and lie on the sphere.
    let mut contacts = 0;
    for _ in 0..60 {
        contacts = sim.step().unwrap().self_contacts;
    }
    assert!(contacts > 0, "no contacts: the test tests nothing");
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let steps = 150;
    let mut fewest = usize::MAX;
    let mut impacts = 0;
    for _ in 0..steps {
        let stats = sim.step().unwrap();
        fewest = fewest.min(stats.self_contacts);
        impacts += stats.self_impacts;
    }
    let count = ALLOCATIONS.load(Ordering::Relaxed) - before;
    println!("layers: {count} allocations in {steps} steps, at least {fewest} contacts and {impacts} impacts in all");
    assert!(
        fewest > 0 && impacts > 0,
        "no contacts or no impacts: the test tests less than it says"
    );
    assert!(
        count <= 4,
        "allocated {count} times in {steps} steps with layers in contact"
    );
}
