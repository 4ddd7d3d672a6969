//! The noise measure (method.md section 2, "Noise"): high-rate arm demos
//! with measurement noise are named with the `--sg-seconds` that smooths
//! them, which then clears the notice; clean high-rate demos and the
//! bundled samples are not named.

use dmpscope_core::arrange::streams::load_source;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::SourceData;
use dmpscope_core::prepare::noise::NOISE_DOMINATES;
use dmpscope_core::rng::Rng;
use dmpscope_core::{Built, PrepSettings, RawDemo, TimeSource, Unusable, build_model};

/// Kinesthetic demos of an arm at 515 Hz: minimum-jerk reaches of 0.3-0.5 m
/// over 2-3 s, with `noise_m` of white measurement noise on each axis.
fn arm_demos(noise_m: f64) -> Vec<RawDemo> {
    let mut rng = Rng::new(5);
    (0..6)
        .map(|i| {
            let duration = 2.0 + 0.2 * i as f64;
            let goal = [0.3 + 0.04 * i as f64, 0.1 - 0.03 * i as f64, 0.2];
            let n = (duration * 515.0) as usize + 1;
            let mut stamps = Vec::with_capacity(n);
            let mut positions = Vec::with_capacity(n);
            for k in 0..n {
                let t = k as f64 / 515.0;
                let s = (t / duration).min(1.0);
                let shape = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
                stamps.push((t * 1e9).round() as i64);
                positions.push(
                    std::array::from_fn::<f64, 3, _>(|ax| {
                        goal[ax] * shape + noise_m * rng.normal()
                    })
                    .into(),
                );
            }
            RawDemo {
                name: format!("franka.mcap:/demo_{i}"),
                file: "franka.mcap".into(),
                topic: format!("/demo_{i}"),
                stamps_ns: stamps,
                positions,
                orientations: None,
                time_source: TimeSource::HeaderStamp,
            }
        })
        .collect()
}

fn build(demos: &[RawDemo], prep: &PrepSettings) -> Built {
    build_model(demos, prep, Default::default(), Unusable::Fail).expect("model")
}

fn noise_notice(built: &Built) -> Option<String> {
    built
        .notices
        .iter()
        .map(ToString::to_string)
        .find(|n| n.contains("mostly noise"))
}

#[test]
fn noisy_high_rate_demos_are_named_and_the_suggested_window_clears_it() {
    let demos = arm_demos(0.0002);
    let built = build(&demos, &PrepSettings::default());
    let notice = noise_notice(&built).expect("a noise notice");
    eprintln!("{notice}");
    assert!(notice.contains("6 demos (franka.mcap:/demo_0"), "{notice}");
    let suggested = built
        .model
        .demos()
        .iter()
        .map(|d| {
            assert!(d.acc_noise.expect("measured") > NOISE_DOMINATES, "{d:?}");
            d.suggested_sg_seconds.expect("a window that smooths it")
        })
        .fold(0.0f64, f64::max);
    assert!(
        notice.contains(&format!("--sg-seconds {suggested}")),
        "{notice}"
    );
    let fixed = PrepSettings {
        sg_seconds: Some(suggested),
        ..PrepSettings::default()
    };
    let rebuilt = build(&demos, &fixed);
    assert_eq!(noise_notice(&rebuilt), None);
    for d in rebuilt.model.demos() {
        assert!(d.acc_noise.expect("measured") < NOISE_DOMINATES, "{d:?}");
    }
}

#[test]
fn clean_high_rate_demos_and_the_bundled_samples_are_not_named() {
    let clean = build(&arm_demos(0.0), &PrepSettings::default());
    assert_eq!(noise_notice(&clean), None);
    for d in clean.model.demos() {
        assert!(d.acc_noise.expect("measured") < 0.1, "{d:?}");
    }
    for (name, bytes) in [
        (
            "reach10.mcap",
            &include_bytes!("../../assets/reach10.mcap")[..],
        ),
        (
            "planted8.mcap",
            &include_bytes!("../../assets/planted8.mcap")[..],
        ),
    ] {
        let demos = load_source(name, SourceData::Bytes(bytes), &LoadOptions::default())
            .expect("sample")
            .demos;
        let built = build(&demos, &PrepSettings::default());
        assert_eq!(noise_notice(&built), None, "{name}");
    }
}
