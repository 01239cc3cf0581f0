use turntable::engine::solve::*;
use turntable::engine::*;
fn main() {
    let t0 = std::time::Instant::now();
    for xi0 in [0.8, 0.5, 0.2, 0.001] {
        for tol in [1e-9, 1e-11] {
            let (phi, v) = easiest_angle(xi0, 72, Settings::dp54(tol), 1e-10, 1e-4).unwrap();
            println!("xi0 {xi0} tol {tol} argmin {phi:.5} vmin {v:.10} t {:?}", t0.elapsed());
        }
    }
}
