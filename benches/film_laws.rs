//! `cargo bench --bench film_laws`: the cost of one long-bearing film force (docs/physics.md §4),
//! the closed form (Gümbel condition) against the graded Gauss–Legendre quadrature it replaced
//! in the right-hand side, over a sweep of eccentricities, squeeze and wedge speeds.

use std::hint::black_box;
use std::time::Duration;

use clearsim::laws::{long_bearing_force, long_bearing_force_quadrature, BearingGeometry, FilmState};
use criterion::{criterion_group, criterion_main, Criterion};

const G: BearingGeometry = BearingGeometry { viscosity: 0.4, journal_radius: 0.01, clearance: 5e-4, length: 0.05 };

/// 100 film states from ε = 0.05 to 0.95, squeeze ε̇ from −3 to 7 1/s, wedge from 80 to −20 rad/s.
fn states() -> Vec<FilmState> {
    (0..100)
        .map(|i| {
            let x = i as f64 / 100.0;
            FilmState { eps: 0.05 + 0.9 * x, eps_dot: (x - 0.3) * 10.0, wedge: 80.0 - 100.0 * x }
        })
        .collect()
}

fn bench_long_bearing(c: &mut Criterion) {
    let states = states();
    let mut g = c.benchmark_group("long_bearing_100_states");
    g.warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    g.bench_function("closed_form", |b| b.iter(|| states.iter().map(|s| long_bearing_force(&G, black_box(*s)).0).sum::<f64>()));
    g.bench_function("quadrature", |b| b.iter(|| states.iter().map(|s| long_bearing_force_quadrature(&G, black_box(*s)).0).sum::<f64>()));
    g.finish();
}

criterion_group!(benches, bench_long_bearing);
criterion_main!(benches);
