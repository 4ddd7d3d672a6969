//! The recordings the user opened and what each gave: its streams, read in
//! the background with the current loading options, and its demos, the
//! streams grouped as the options say. A source stays in the list whatever
//! happens to it, so a changed option reloads it and nothing the user opened
//! is lost.

use std::path::PathBuf;
use std::sync::{Arc, LazyLock};

use dmpscope_core::arrange::streams::{Arrangement, Overrides, StreamInfo, arrange};
use dmpscope_core::load::options::{LoadOptions, UpAxis};
use dmpscope_core::load::source::{SourceData, SourceStreams, load_streams};
use dmpscope_core::{Level, Notice, RawDemo};

use crate::jobs::{Once, Runner};
use crate::stage::{Polled, Stage};

/// The bundled samples' bytes, shared by every source made of them.
static REACH10: LazyLock<Arc<[u8]>> =
    LazyLock::new(|| Arc::from(&include_bytes!("../../assets/reach10.mcap")[..]));
static PLANTED8: LazyLock<Arc<[u8]>> =
    LazyLock::new(|| Arc::from(&include_bytes!("../../assets/planted8.mcap")[..]));

/// A recording to load: a file or folder on disk, or bytes with a name (a
/// browser upload or drop, a bundled sample).
#[derive(Clone, Debug)]
pub enum Source {
    /// A path: a file, or a folder (rosbag2 or any folder of `.mcap`).
    Path(PathBuf),
    /// Bytes and the file's name.
    Bytes {
        /// The file name (shown, and its extension picks the reader).
        name: String,
        /// The contents.
        bytes: Arc<[u8]>,
    },
}

impl Source {
    /// The bundled reach sample (10 tracked human reaches whose J is flat),
    /// built into the program (native and web alike). The app opens on
    /// [`Source::planted_sample`].
    pub fn sample() -> Self {
        Self::bundled("reach10.mcap", &REACH10)
    }

    /// The bundled planted-gain sample: 8 demos integrated from one DMP
    /// at the paper's gains 10.73 / 20.71, 0.1 mm noise (`dmpscope
    /// gen-sample --planted`), on which the method recovers the gains.
    pub fn planted_sample() -> Self {
        Self::bundled("planted8.mcap", &PLANTED8)
    }

    fn bundled(name: &str, bytes: &LazyLock<Arc<[u8]>>) -> Self {
        Self::Bytes {
            name: name.into(),
            bytes: Arc::clone(bytes),
        }
    }

    /// The bundled samples: their names and what they show.
    pub fn samples() -> [(Self, &'static str); 2] {
        [
            (
                Self::planted_sample(),
                "planted8: 8 demos from one DMP at D/M 10.73, K/M 20.71 (the method recovers them)",
            ),
            (
                Self::sample(),
                "reach10: 10 tracked reaches, J flat: what the demos allow, and a pick",
            ),
        ]
    }

    /// Whether this is one of the bundled samples (their bytes, not a file
    /// that happens to share a name).
    pub fn is_sample(&self) -> bool {
        matches!(self, Self::Bytes { bytes, .. }
            if Arc::ptr_eq(bytes, &REACH10) || Arc::ptr_eq(bytes, &PLANTED8))
    }

    /// The name shown for the source.
    pub fn name(&self) -> String {
        match self {
            Self::Path(p) => p.display().to_string(),
            Self::Bytes { name, .. } => name.clone(),
        }
    }

    /// Loads the source's streams (the core's `load_streams`, as the CLI).
    pub fn load(&self, options: &LoadOptions) -> Result<SourceStreams, String> {
        let name = self.name();
        let data = match self {
            Self::Path(p) => SourceData::Path(p),
            Self::Bytes { bytes, .. } => SourceData::Bytes(bytes),
        };
        load_streams(&name, data, options).map_err(|e| e.to_string())
    }
}

/// What decides a source's streams: the options the reader applies.
#[derive(Clone, Debug, PartialEq)]
pub struct StreamKey {
    /// TF child frames / pose indices kept.
    pub frames: Vec<String>,
    /// The up axis.
    pub up: UpAxis,
    /// The frame TF transforms are expressed in.
    pub fixed_frame: Option<String>,
    /// The positions' unit.
    pub units: dmpscope_core::load::units::Units,
    /// Whether a bad orientation drops it instead of stopping the load.
    pub drop_bad_orientation: bool,
}

impl StreamKey {
    /// The key of `options`.
    pub fn of(options: &LoadOptions) -> Self {
        Self {
            frames: options.frames.clone(),
            up: options.up,
            fixed_frame: options.fixed_frame.clone(),
            units: options.units,
            drop_bad_orientation: options.drop_bad_orientation,
        }
    }

    fn options(&self) -> LoadOptions {
        LoadOptions {
            frames: self.frames.clone(),
            up: self.up,
            fixed_frame: self.fixed_frame.clone(),
            units: self.units,
            drop_bad_orientation: self.drop_bad_orientation,
            ..LoadOptions::default()
        }
    }
}

/// What turns a source's streams into demos without reading again: the
/// topic filter, what a break in time does and the grouping, and the user's
/// ticks in the Recording panel.
type Regrouping = (Arrangement, Overrides);

/// A loaded source's streams and the options they were read with.
struct Streams {
    key: StreamKey,
    result: Result<SourceStreams, String>,
}

/// One opened recording.
pub struct SourceSlot {
    /// The recording.
    pub source: Source,
    streams: Option<Streams>,
    /// The load under way (its value is moved to `streams` when done).
    load: Stage<StreamKey, Result<SourceStreams, String>>,
    /// The demos of the streams for an arrangement, and those.
    grouped: Stage<Regrouping, Vec<RawDemo>>,
    /// Every stream and what became of it, for the arrangement.
    streams_info: Vec<StreamInfo>,
    /// The user's choice per stream (topic), over the filter.
    pub overrides: Overrides,
}

/// What changed in a slot during [`SourceSlot::update`].
#[derive(Default)]
pub struct SlotNews {
    /// Loads started.
    pub loads_started: usize,
    /// Whether its demos may have changed (they were regrouped).
    pub demos_changed: bool,
    /// Whether its demos were regrouped.
    pub regrouped: bool,
    /// What to tell the user.
    pub notices: Vec<Notice>,
}

impl SourceSlot {
    /// A slot for `source`, not loaded yet.
    pub fn new(source: Source) -> Self {
        Self {
            source,
            streams: None,
            load: Stage::default(),
            grouped: Stage::default(),
            streams_info: Vec::new(),
            overrides: Overrides::new(),
        }
    }

    /// Every stream the source holds and what became of it (empty until
    /// loaded).
    pub fn streams(&self) -> &[StreamInfo] {
        &self.streams_info
    }

    /// The streams as read, before they are arranged into demos (the
    /// Recording section's timelines).
    pub fn raw_streams(&self) -> &[RawDemo] {
        match &self.streams {
            Some(Streams {
                result: Ok(loaded), ..
            }) => &loaded.demos,
            _ => &[],
        }
    }

    /// The topics the reader skipped (they hold no pose, or are not
    /// demonstrations), with why.
    pub fn skipped_topics(&self) -> &[(String, String)] {
        match &self.streams {
            Some(Streams {
                result: Ok(loaded), ..
            }) => &loaded.skipped,
            _ => &[],
        }
    }

    /// The error that stopped the source's load, if one did.
    pub fn error(&self) -> Option<&str> {
        match &self.streams {
            Some(Streams { result: Err(e), .. }) => Some(e),
            _ => None,
        }
    }

    /// Whether the slot is being (re)loaded.
    pub fn loading(&self) -> bool {
        self.load.running()
    }

    /// The demos the slot gives now (none while it first loads or when it
    /// failed).
    pub fn demos(&self) -> &[RawDemo] {
        self.grouped.value().map_or(&[], Vec::as_slice)
    }

    /// Brings the slot to `options`: starts a load when the stream options
    /// changed (cancelling one under way for other options), takes a finished
    /// load, and regroups when the streams or the grouping changed.
    pub fn update(&mut self, options: &LoadOptions, runner: &Runner) -> SlotNews {
        let mut news = SlotNews::default();
        let key = StreamKey::of(options);
        let current = self.streams.as_ref().is_some_and(|s| s.key == key);
        if current && self.load.running() {
            // Back to the options the streams were read with: a load for
            // other options is stale (dropping it cancels it).
            self.load.clear();
        }
        let source = &self.source;
        if !current
            && self.load.ensure_job(key.clone(), || {
                let (source, load_options) = (source.clone(), key.options());
                let work = Once::new(move || source.load(&load_options));
                Ok(runner.start("loading", work))
            })
        {
            if let Some(n) = self.load.take_notice() {
                news.notices.push(Notice::warning(n));
            }
            news.loads_started += 1;
        }
        let finished = match self.load.poll() {
            Polled::Value => self.load.take_value(),
            Polled::Failed(e) => Some(Err(format!("{}: {e}", self.source.name()))),
            Polled::Nothing => None,
        };
        if let (Some(result), Some(key)) = (finished, self.load.key().cloned()) {
            match &result {
                Ok(loaded) => news.notices.extend(
                    loaded
                        .notices
                        .iter()
                        .filter(|n| n.level != Level::Detail)
                        .cloned(),
                ),
                Err(e) => news.notices.push(Notice::error(e.clone())),
            }
            self.streams = Some(Streams { key, result });
            self.grouped.clear();
        }
        let Some(streams) = &self.streams else {
            return news;
        };
        let how = (Arrangement::of(options), self.overrides.clone());
        let (source, info, notices) = (&self.source, &mut self.streams_info, &mut news.notices);
        let regrouped = self.grouped.ensure_now(how, |how| {
            let loaded = streams.result.as_ref()?;
            let arranged = arrange(loaded.demos.clone(), &how.0, &how.1).map_err(|e| {
                notices.push(Notice::error(e.to_string()));
                e.to_string()
            })?;
            notices.extend(arranged.notices);
            *info = arranged.streams;
            if arranged.demos.is_empty() && !loaded.demos.is_empty() {
                notices.push(Notice::warning(format!(
                    "{}: segmentation found no movement between rests (lower the rest speed \
                     or the shortest demo in Loading)",
                    source.name()
                )));
            }
            Ok(arranged.demos)
        });
        news.demos_changed |= regrouped;
        news.regrouped |= regrouped;
        news
    }
}
