use std::hint::black_box;
use std::time::Instant;
fn time(f: &dyn Fn() -> f64) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..200 {
        let s = Instant::now();
        black_box(f());
        best = best.min(s.elapsed().as_secs_f64());
    }
    best / 10000.0 * 1e9
}
fn main() {
    for amp in [0.3f64, 1.0, 3.0] {
        let lat_std = time(&|| {
            let mut x = black_box(amp);
            for _ in 0..10000 {
                x = amp * x.sin() + 0.0 * x;
                x = x + amp * 0.3;
            }
            x
        });
        let lat_fast = time(&|| {
            let mut x = black_box(amp);
            for _ in 0..10000 {
                x = amp * mbd_core::trig::sin(x) + 0.0 * x;
                x = x + amp * 0.3;
            }
            x
        });
        let thr_std = time(&|| {
            let mut a = 0.0;
            for i in 0..10000 {
                let x = amp * (i as f64 * 1e-4);
                let (s, c) = x.sin_cos();
                a += s + c;
            }
            a
        });
        let thr_fast = time(&|| {
            let mut a = 0.0;
            for i in 0..10000 {
                let x = amp * (i as f64 * 1e-4);
                let (s, c) = mbd_core::trig::sin_cos(x);
                a += s + c;
            }
            a
        });
        println!(
            "amp {amp}: latency sin std {lat_std:.1} ns, trig {lat_fast:.1} ns; throughput sin_cos std {thr_std:.1} ns, trig {thr_fast:.1} ns"
        );
    }
}
