//! Measured samples: direction pairs in structure-of-arrays storage, values per
//! channel, per-sample weights, and filters that report what they dropped.

use nalgebra::Vector3;

use crate::{CoreError, Direction};

/// Direction pairs `(L, V)` stored as six coordinate arrays, so batch
/// evaluation streams through memory.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DirPairs {
    /// `L.x` of every pair
    pub lx: Vec<f64>,
    /// `L.y`
    pub ly: Vec<f64>,
    /// `L.z` (`cos theta_i`)
    pub lz: Vec<f64>,
    /// `V.x`
    pub vx: Vec<f64>,
    /// `V.y`
    pub vy: Vec<f64>,
    /// `V.z` (`cos theta_o`)
    pub vz: Vec<f64>,
}

/// A run of consecutive pairs of a [`DirPairs`] ([`DirPairs::chunk`]).
#[derive(Clone, Copy, Debug)]
pub struct PairChunk<'a> {
    lx: &'a [f64],
    ly: &'a [f64],
    lz: &'a [f64],
    vx: &'a [f64],
    vy: &'a [f64],
    vz: &'a [f64],
}

impl PairChunk<'_> {
    /// `L` and `V` of the chunk's pair `i`.
    #[inline(always)]
    pub fn at(&self, i: usize) -> (Vector3<f64>, Vector3<f64>) {
        (
            Vector3::new(self.lx[i], self.ly[i], self.lz[i]),
            Vector3::new(self.vx[i], self.vy[i], self.vz[i]),
        )
    }
}

impl DirPairs {
    /// Empty storage with room for `n` pairs.
    pub fn with_capacity(n: usize) -> Self {
        DirPairs {
            lx: Vec::with_capacity(n),
            ly: Vec::with_capacity(n),
            lz: Vec::with_capacity(n),
            vx: Vec::with_capacity(n),
            vy: Vec::with_capacity(n),
            vz: Vec::with_capacity(n),
        }
    }

    /// The `len` pairs from `start` on, copied (for kernels that work on
    /// cache-sized blocks of a large set).
    ///
    /// # Panics
    /// If `start + len > self.len()`.
    pub fn range(&self, start: usize, len: usize) -> DirPairs {
        let cut = |v: &[f64]| v[start..start + len].to_vec();
        DirPairs {
            lx: cut(&self.lx),
            ly: cut(&self.ly),
            lz: cut(&self.lz),
            vx: cut(&self.vx),
            vy: cut(&self.vy),
            vz: cut(&self.vz),
        }
    }

    /// The `len` pairs from `start` on, borrowed as slices of one length:
    /// what a kernel's loop over a chunk reads, with no bounds check left
    /// in it (so the loop can vectorise).
    ///
    /// # Panics
    /// If `start + len > self.len()`.
    #[inline(always)]
    pub fn chunk(&self, start: usize, len: usize) -> PairChunk<'_> {
        let r = start..start + len;
        PairChunk {
            lx: &self.lx[r.clone()],
            ly: &self.ly[r.clone()],
            lz: &self.lz[r.clone()],
            vx: &self.vx[r.clone()],
            vy: &self.vy[r.clone()],
            vz: &self.vz[r],
        }
    }

    /// Append a pair.
    pub fn push(&mut self, l: &Vector3<f64>, v: &Vector3<f64>) {
        self.lx.push(l.x);
        self.ly.push(l.y);
        self.lz.push(l.z);
        self.vx.push(v.x);
        self.vy.push(v.y);
        self.vz.push(v.z);
    }

    /// Remove every pair, keeping the storage.
    pub fn clear(&mut self) {
        for a in [
            &mut self.lx,
            &mut self.ly,
            &mut self.lz,
            &mut self.vx,
            &mut self.vy,
            &mut self.vz,
        ] {
            a.clear();
        }
    }

    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.lx.len()
    }

    /// True when there are no pairs.
    pub fn is_empty(&self) -> bool {
        self.lx.is_empty()
    }

    /// `L` of pair `j`.
    #[inline]
    pub fn l(&self, j: usize) -> Vector3<f64> {
        Vector3::new(self.lx[j], self.ly[j], self.lz[j])
    }

    /// `V` of pair `j`.
    #[inline]
    pub fn v(&self, j: usize) -> Vector3<f64> {
        Vector3::new(self.vx[j], self.vy[j], self.vz[j])
    }

    /// The pairs with `L` and `V` swapped (for reciprocity checks).
    pub fn swapped(&self) -> DirPairs {
        DirPairs {
            lx: self.vx.clone(),
            ly: self.vy.clone(),
            lz: self.vz.clone(),
            vx: self.lx.clone(),
            vy: self.ly.clone(),
            vz: self.lz.clone(),
        }
    }

    fn select(&self, keep: &[bool]) -> DirPairs {
        let pick = |a: &[f64]| -> Vec<f64> {
            a.iter()
                .zip(keep)
                .filter(|(_, k)| **k)
                .map(|(x, _)| *x)
                .collect()
        };
        DirPairs {
            lx: pick(&self.lx),
            ly: pick(&self.ly),
            lz: pick(&self.lz),
            vx: pick(&self.vx),
            vy: pick(&self.vy),
            vz: pick(&self.vz),
        }
    }
}

/// What a filter did: how many samples it kept and dropped, and why.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FilterReport {
    /// samples kept
    pub kept: usize,
    /// samples dropped because a direction exceeded the angle limit
    pub dropped_angle: usize,
    /// samples dropped because a value was NaN or infinite
    pub dropped_non_finite: usize,
    /// samples dropped because a value was negative (only when asked)
    pub dropped_negative: usize,
}

impl FilterReport {
    /// Total dropped.
    pub fn dropped(&self) -> usize {
        self.dropped_angle + self.dropped_non_finite + self.dropped_negative
    }
}

/// A set of measured samples `(L, V, value[c], weight)`.
///
/// Values are stored per channel (`channel(c)[j]`), so a fit streams through one
/// channel at a time. Weights default to 1 (scattered data); gridded data sets
/// carry their cells' solid angles (see [`crate::weights`]).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SampleSet {
    /// Short name (`curet#25`, `cayman`).
    pub name: String,
    /// Where the samples come from (file, database, transformation applied).
    pub provenance: String,
    /// Channel names (`["grey"]`, `["r", "g", "b"]`, `["Y"]`).
    pub channel_names: Vec<String>,
    /// What a reader assumed that the caller should tell the user, one line
    /// each, naming the file (e.g. a CSV file without a weight column read
    /// with unit weights). Empty when the file said everything.
    pub notes: Vec<String>,
    pairs: DirPairs,
    values: Vec<Vec<f64>>,
    weights: Vec<f64>,
}

impl SampleSet {
    /// An empty set with the given channels.
    pub fn new(
        name: impl Into<String>,
        provenance: impl Into<String>,
        channel_names: Vec<String>,
    ) -> Self {
        let nc = channel_names.len();
        SampleSet {
            name: name.into(),
            provenance: provenance.into(),
            channel_names,
            notes: Vec::new(),
            pairs: DirPairs::default(),
            values: vec![Vec::new(); nc],
            weights: Vec::new(),
        }
    }

    /// Append a sample. Values are stored as given (negative and NaN values
    /// included: filters decide, and report); the weight must be finite and
    /// non-negative.
    pub fn push(
        &mut self,
        l: &Direction,
        v: &Direction,
        values: &[f64],
        weight: f64,
    ) -> Result<(), CoreError> {
        if values.len() != self.channels() {
            return Err(CoreError::ChannelCount {
                set: self.name.clone(),
                index: self.len(),
                expected: self.channels(),
                got: values.len(),
            });
        }
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(CoreError::InvalidWeight {
                set: self.name.clone(),
                index: self.len(),
                weight,
            });
        }
        self.pairs.push(l.vector(), v.vector());
        for (c, x) in values.iter().enumerate() {
            self.values[c].push(*x);
        }
        self.weights.push(weight);
        Ok(())
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// True when the set holds no sample.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Number of channels.
    pub fn channels(&self) -> usize {
        self.channel_names.len()
    }

    /// The direction pairs.
    pub fn pairs(&self) -> &DirPairs {
        &self.pairs
    }

    /// Values of channel `c`.
    pub fn channel(&self, c: usize) -> &[f64] {
        &self.values[c]
    }

    /// Values in channel-major order (`[c * n + j]`), the order of model batch
    /// output and of residual vectors.
    pub fn values_channel_major(&self) -> Vec<f64> {
        self.values.concat()
    }

    /// Per-sample weights.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Replace the weights (e.g. by solid-angle weights); each must be finite
    /// and non-negative.
    pub fn set_weights(&mut self, weights: Vec<f64>) -> Result<(), CoreError> {
        if weights.len() != self.len() {
            return Err(CoreError::LengthMismatch {
                what: "weights vs samples",
                left: weights.len(),
                right: self.len(),
            });
        }
        if let Some((index, &weight)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !(w.is_finite() && **w >= 0.0))
        {
            return Err(CoreError::InvalidWeight {
                set: self.name.clone(),
                index,
                weight,
            });
        }
        self.weights = weights;
        Ok(())
    }

    /// Count samples with a negative (finite) value in any channel.
    pub fn count_negative(&self) -> usize {
        (0..self.len())
            .filter(|&j| self.values.iter().any(|ch| ch[j] < 0.0))
            .count()
    }

    /// Count samples with a NaN or infinite value in any channel.
    pub fn count_non_finite(&self) -> usize {
        (0..self.len())
            .filter(|&j| self.values.iter().any(|ch| !ch[j].is_finite()))
            .count()
    }

    /// Keep only the samples where `keep[j]` holds.
    pub fn select(&self, keep: &[bool]) -> SampleSet {
        SampleSet {
            name: self.name.clone(),
            provenance: self.provenance.clone(),
            channel_names: self.channel_names.clone(),
            notes: self.notes.clone(),
            pairs: self.pairs.select(keep),
            values: self
                .values
                .iter()
                .map(|ch| {
                    ch.iter()
                        .zip(keep)
                        .filter(|(_, k)| **k)
                        .map(|(x, _)| *x)
                        .collect()
                })
                .collect(),
            weights: self
                .weights
                .iter()
                .zip(keep)
                .filter(|(_, k)| **k)
                .map(|(x, _)| *x)
                .collect(),
        }
    }

    /// Drop samples whose incident or outgoing polar angle exceeds `limit`
    /// (radians), and samples with a direction at or below the horizon.
    pub fn filter_angle_limit(&self, limit: f64) -> (SampleSet, FilterReport) {
        let cos_limit = limit.cos();
        let keep: Vec<bool> = (0..self.len())
            .map(|j| {
                let (ci, co) = (self.pairs.lz[j], self.pairs.vz[j]);
                ci > 0.0 && co > 0.0 && ci >= cos_limit - 1e-12 && co >= cos_limit - 1e-12
            })
            .collect();
        let kept = keep.iter().filter(|k| **k).count();
        let report = FilterReport {
            kept,
            dropped_angle: self.len() - kept,
            ..FilterReport::default()
        };
        (self.select(&keep), report)
    }

    /// Drop samples with a NaN or infinite value in any channel and, when
    /// `drop_negative`, those with a negative value (MERL's `-1` marker).
    /// Negative values are otherwise kept: CUReT's slightly negative values
    /// are measurement noise, i.e. data.
    pub fn filter_invalid(&self, drop_negative: bool) -> (SampleSet, FilterReport) {
        let mut report = FilterReport::default();
        let keep: Vec<bool> = (0..self.len())
            .map(|j| {
                if self.values.iter().any(|ch| !ch[j].is_finite()) {
                    report.dropped_non_finite += 1;
                    false
                } else if drop_negative && self.values.iter().any(|ch| ch[j] < 0.0) {
                    report.dropped_negative += 1;
                    false
                } else {
                    true
                }
            })
            .collect();
        report.kept = self.len() - report.dropped();
        (self.select(&keep), report)
    }

    /// The mean of all channels as a one-channel set (Sopp's monochrome
    /// stage; CUReT's `abrdf.dat` is this mean).
    pub fn mean_channel(&self) -> SampleSet {
        let nc = self.channels().max(1) as f64;
        let mean: Vec<f64> = (0..self.len())
            .map(|j| self.values.iter().map(|ch| ch[j]).sum::<f64>() / nc)
            .collect();
        SampleSet {
            name: self.name.clone(),
            provenance: format!("{} (mean of {} channels)", self.provenance, self.channels()),
            channel_names: vec!["grey".to_string()],
            notes: self.notes.clone(),
            pairs: self.pairs.clone(),
            values: vec![mean],
            weights: self.weights.clone(),
        }
    }

    /// Channel `c` alone as a one-channel set.
    pub fn single_channel(&self, c: usize) -> SampleSet {
        SampleSet {
            name: format!("{}[{}]", self.name, self.channel_names[c]),
            provenance: self.provenance.clone(),
            channel_names: vec![self.channel_names[c].clone()],
            notes: self.notes.clone(),
            pairs: self.pairs.clone(),
            values: vec![self.values[c].clone()],
            weights: self.weights.clone(),
        }
    }

    /// Smallest and largest finite value over all channels, if any.
    pub fn value_range(&self) -> Option<(f64, f64)> {
        let mut it = self.values.iter().flatten().filter(|x| x.is_finite());
        let first = *it.next()?;
        Some(it.fold((first, first), |(lo, hi), &x| (lo.min(x), hi.max(x))))
    }
}
