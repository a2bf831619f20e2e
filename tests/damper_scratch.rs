use thud::damper::*;
#[test]
fn scratch() {
    let p = DamperParams::table2();
    let t0 = std::time::Instant::now();
    let r = simulate(&p, Solver::Event, &RunOptions::default()).unwrap();
    println!("event {:?} impacts {}", t0.elapsed(), r.impacts.len());
    for i in r.impacts.iter().take(6) {
        println!("{:?}", i);
    }
    println!("maxima {:?}", &r.maxima[..r.maxima.len().min(5)]);
    println!("energy {:?} zmax {}", r.energy, r.zdot_abs_max_m_s);
    let mut q = p;
    q.duration_s = 0.05;
    let t0 = std::time::Instant::now();
    let r = simulate(&q, Solver::Newmark { dt_s: 1e-7 }, &RunOptions::default()).unwrap();
    println!("newmark {:?} impacts {}", t0.elapsed(), r.impacts.len());
    for i in r.impacts.iter().take(6) {
        println!("{:?}", i);
    }
    for m in [0.01, 0.03, 0.05, 0.1] {
        let s = single_contact(m, 0.5, 5.6e8, 20.0, false, 1.4);
        let sn = single_contact(m, 0.5, 5.6e8, 20.0, true, 1.4);
        println!("m {m} R {} Rnt {} {:?}", s.u_out_m_s / 1.4, sn.u_out_m_s / 1.4, s);
    }
}
