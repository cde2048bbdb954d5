//! The model's warnings travel with the predictions (docs/measurements.md, "Warnings of the model, per series"): each kind once, its rows counted per series, rows sharing an operating point counted each.
use crate::common::{preset, with_grid};
use ecf_measure::evaluate::{predict_warned, warnings_text};
use ecf_measure::measure::{Dataset, Defaults};

const SLIDE: &str = "cx [-],f,series,v_mps,fn_kN
-0.95,-0.3,A,10,110
-0.95,-0.3,A,10,110
-0.92,-0.3,A,10,110
-0.5,-0.3,A,10,110
-0.01,-0.3,B,20,110
-0.93,-0.3,B,20,110
-0.02,-0.35,B,20,110
";

#[test]
fn wheel_slide_warnings_are_counted_per_series() {
    let data = Dataset::from_csv_str(SLIDE, "slide.csv", &Defaults::default()).unwrap();
    let cfg = with_grid(preset("dry"), 20, 7);
    let (pred, ws) = predict_warned(&cfg, &data, 2).unwrap();
    assert_eq!(pred.len(), 7);
    let slide: Vec<_> = ws
        .iter()
        .filter(|w| w.message.starts_with("wheel surface speed"))
        .collect();
    assert_eq!(slide.len(), 1, "{ws:#?}");
    let s = slide[0];
    // |1 + c_x| < 0.1: lines 2, 3 (the same point twice), 4 in A; line 7 in B
    assert_eq!(s.rows, 4);
    assert_eq!(s.per_series.len(), 2);
    assert_eq!(
        (s.per_series[0].series.as_str(), s.per_series[0].rows),
        ("A", 3)
    );
    assert_eq!(s.per_series[0].lines, vec![2, 3, 4]);
    assert_eq!(
        (s.per_series[1].series.as_str(), s.per_series[1].rows),
        ("B", 1)
    );
    assert_eq!(s.per_series[1].lines, vec![7]);
    let t = warnings_text(&ws);
    assert!(
        t.contains("series A: 3 row(s)") && t.contains("surface_time_flash"),
        "{t}"
    );
    // with the wheel-slide effect on, the model does not warn
    let mut on = cfg.clone();
    on.effects.insert(creep_core::Effect::SurfaceTimeFlash);
    let (_, ws) = predict_warned(&on, &data, 1).unwrap();
    assert!(
        ws.iter()
            .all(|w| !w.message.starts_with("wheel surface speed")),
        "{ws:#?}"
    );
}
