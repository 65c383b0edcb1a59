use contopt_scene::{Scene, BUNDLED};

#[test]
fn bundled_parse() {
    for b in BUNDLED {
        match Scene::bundled(b.name) {
            Ok(s) => eprintln!("{}: {} cases", b.name, s.cases().len()),
            Err(e) => panic!("{}: {e}", b.name),
        }
    }
}

#[test]
fn quick_runs() {
    for name in ["hertz", "flat-punch", "punch-on-block", "paper-table1", "winkler-bed", "steel-on-aluminium", "paper-table2", "paper-table3"] {
        let scene = Scene::bundled(name).unwrap();
        for r in scene.run() {
            let r = r.unwrap();
            eprintln!("{name} {}: {:?} p_max {:?} bound {:?} dh {:?} {} warn {:?} limit {:?} hertz {:?} res {:?}", r.label, r.status, r.p_max_mpa, r.bound_p_max_mpa, r.dh_max_um, r.termination, r.warnings, r.limit.as_ref().map(|l| &l.message), r.hertz, r.resolution);
        }
    }
}

#[test]
#[ignore]
fn rollers() {
    for name in ["roller", "roller-study"] {
        let scene = Scene::bundled(name).unwrap();
        for r in scene.run() {
            let r = r.unwrap();
            let roller = r.roller.as_ref().map(|x| (x.p_max_at_mm, x.edge_loading, x.half_width_mm, x.crown_drop_end_um));
            eprintln!("{name} {}: {:?} p_max {:?} bound {:?} dh {:?} {} warn {:?} hertz {:?} res {:?} roller {:?} t {:?}", r.label, r.status, r.p_max_mpa, r.bound_p_max_mpa, r.dh_max_um, r.termination, r.warnings, r.hertz, r.resolution, roller, r.timings_ms);
        }
    }
}
