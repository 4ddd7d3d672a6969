//! The recordings the user opened and what each gave: its streams, read in
//! the background with the current loading options, and its demos, the
//! streams grouped as the options say. A source stays in the list whatever
//! happens to it, so a changed option reloads it and nothing the user opened
//! is lost.

use std::future::Future;
use std::path::PathBuf;
use std::pin::Pin;
use std::sync::{Arc, LazyLock, Mutex, PoisonError};

use dmpscope_core::arrange::streams::{Arrangement, Overrides, StreamInfo, arrange};
use dmpscope_core::load::access::{FileAt, Meter, Metered, SliceAt, poll_once};
use dmpscope_core::load::options::{LoadOptions, UpAxis};
use dmpscope_core::load::source::{
    SourceData, SourceStreams, folder_of_metadata, load_streams, load_streams_at,
};
use dmpscope_core::{Level, Notice, RawDemo};

use crate::jobs::{Runner, Step, Work};
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
    /// A file read where it is, in slices, by the platform (a browser's
    /// `File`): never held whole.
    Remote(RemoteFile),
}

/// A file the platform reads in slices (a browser's `File`, through
/// `Blob.slice`): its name, its size, and what loads it.
#[derive(Clone, Debug)]
pub struct RemoteFile {
    /// The file name (shown, and its extension picks the reader).
    pub name: String,
    /// Its size in bytes.
    pub size: u64,
    /// What reads it.
    pub loader: Arc<dyn RemoteLoad>,
}

/// Where a load's result arrives.
pub type LoadSlot = Arc<Mutex<Option<Result<SourceStreams, String>>>>;

/// Loads a [`RemoteFile`]'s streams (the core's `load_streams_at` over its
/// slices), off the session: its result arrives in the slot it returns;
/// reads are counted in, and stopped by, `meter`.
pub trait RemoteLoad: Send + Sync + std::fmt::Debug {
    /// Starts loading with `options`.
    fn start(&self, options: LoadOptions, meter: Arc<Meter>) -> LoadSlot;
}

/// Loading a source as a job: a file or bytes in one step, read through a
/// [`Meter`] (progress, cancel); a remote file by waiting for its result.
pub struct LoadWork {
    state: LoadState,
    meter: Arc<Meter>,
}

enum LoadState {
    /// The load, ready at its first poll.
    Local(Pin<Box<dyn Future<Output = Result<SourceStreams, String>> + Send>>),
    /// A remote load's result slot.
    Remote(LoadSlot),
}

impl Work for LoadWork {
    type Output = Result<SourceStreams, String>;

    fn step(&mut self) -> Step<Self::Output> {
        match &mut self.state {
            LoadState::Local(future) => match poll_once(future) {
                Some(result) => Step::Done(result),
                None => Step::Waiting,
            },
            LoadState::Remote(slot) => {
                match slot.lock().unwrap_or_else(PoisonError::into_inner).take() {
                    Some(result) => Step::Done(result),
                    None => Step::Waiting,
                }
            }
        }
    }
}

impl Drop for LoadWork {
    fn drop(&mut self) {
        // A load dropped (new options, the source closed) stops reading.
        self.meter
            .cancel
            .store(true, std::sync::atomic::Ordering::Relaxed);
    }
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
            Self::Remote(f) => f.name.clone(),
        }
    }

    /// The size in bytes of a single file (`None`: a folder, or unknown).
    pub fn size(&self) -> Option<u64> {
        match self {
            Self::Path(p) => std::fs::metadata(p)
                .ok()
                .filter(|m| m.is_file())
                .map(|m| m.len()),
            Self::Bytes { bytes, .. } => Some(bytes.len() as u64),
            Self::Remote(f) => Some(f.size),
        }
    }

    /// The load of the source's streams as a job (the core's
    /// `load_streams_at`, as the CLI), counted in `meter`.
    pub fn loader(&self, options: LoadOptions, meter: Arc<Meter>) -> LoadWork {
        let name = self.name();
        let state = match self.clone() {
            Self::Remote(f) => LoadState::Remote(f.loader.start(options, Arc::clone(&meter))),
            Self::Bytes { bytes, .. } => {
                let meter = Arc::clone(&meter);
                LoadState::Local(Box::pin(async move {
                    let mut access = Metered::new(SliceAt(&bytes), meter);
                    load_streams_at(&name, &mut access, &options)
                        .await
                        .map_err(|e| e.to_string())
                }))
            }
            // A rosbag2 folder's metadata.yaml stands for the folder.
            Self::Path(p) if p.is_file() && folder_of_metadata(&p).is_none() => {
                let meter = Arc::clone(&meter);
                LoadState::Local(Box::pin(async move {
                    let file = FileAt::open(&p).map_err(|e| format!("{name}: {e}"))?;
                    let mut access = Metered::new(file, meter);
                    load_streams_at(&name, &mut access, &options)
                        .await
                        .map_err(|e| e.to_string())
                }))
            }
            Self::Path(p) => LoadState::Local(Box::pin(async move {
                load_streams(&name, SourceData::Path(&p), &options).map_err(|e| e.to_string())
            })),
        };
        LoadWork { state, meter }
    }

    /// Loads the source's streams at once (the core's `load_streams`, as
    /// the CLI); a remote file cannot be.
    pub fn load(&self, options: &LoadOptions) -> Result<SourceStreams, String> {
        let name = self.name();
        let data = match self {
            Self::Path(p) => SourceData::Path(p),
            Self::Bytes { bytes, .. } => SourceData::Bytes(bytes),
            Self::Remote(_) => return Err(format!("{name}: read in slices only")),
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
    /// The current load's meter (bytes read, cancel).
    meter: Arc<Meter>,
    /// The source's size, when it is one file.
    size: Option<u64>,
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
            meter: Arc::new(Meter::default()),
            size: None,
        }
    }

    /// How far the current load has read: bytes read and the file's size
    /// (`None` when not loading, or for a folder).
    pub fn progress(&self) -> Option<(u64, u64)> {
        let size = self.size?;
        self.load
            .running()
            .then(|| (self.meter.bytes_read().min(size), size))
    }

    /// Stops the current load (it ends as cancelled).
    pub fn cancel(&self) {
        self.meter
            .cancel
            .store(true, std::sync::atomic::Ordering::Relaxed);
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
        let (meter, size) = (&mut self.meter, &mut self.size);
        if !current
            && self.load.ensure_job(key.clone(), || {
                *meter = Arc::new(Meter::default());
                *size = source.size();
                let work = source.loader(key.options(), Arc::clone(meter));
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

#[cfg(test)]
mod tests {
    use super::*;

    fn run(work: &mut LoadWork) -> Result<SourceStreams, String> {
        loop {
            match work.step() {
                Step::Done(result) => return result,
                Step::Working | Step::Waiting | Step::Publish(_) => {}
            }
        }
    }

    #[test]
    fn a_load_counts_what_it_reads_and_a_cancelled_one_ends_as_cancelled() {
        let source = Source::planted_sample();
        let size = source.size().expect("bytes");
        let meter = Arc::new(Meter::default());
        let loaded = run(&mut source.loader(LoadOptions::default(), Arc::clone(&meter)))
            .expect("the sample loads");
        assert_eq!(loaded.demos.len(), 8);
        assert!(
            meter.bytes_read() > 0 && meter.bytes_read() <= size,
            "{} of {size}",
            meter.bytes_read()
        );
        let meter = Arc::new(Meter::default());
        meter
            .cancel
            .store(true, std::sync::atomic::Ordering::Relaxed);
        let err = run(&mut source.loader(LoadOptions::default(), meter)).expect_err("cancelled");
        assert!(
            err.contains("cancelled") && err.contains("planted8.mcap"),
            "{err}"
        );
    }
}
