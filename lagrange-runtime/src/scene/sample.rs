//! Frames of one run: the poses at evenly spaced times of the dense output (the
//! display rate, not the step points), at most [`MAX_FRAMES`] of them.

use nalgebra::{Rotation3, SVector, UnitQuaternion, Vector3};

use crate::error::Error;
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::pose::{BodyPose, Posed};

/// The most frames a run keeps: a minute at 30 frames per second. A longer run
/// is shown at a lower frame rate (the page interpolates between frames), so a
/// page's size does not grow with the run's length or its number of steps.
pub const MAX_FRAMES: usize = 1800;

/// The sampled motion of one run, in f64.
pub(super) struct Frames {
    /// Frame k is at `t0 + k dt`.
    pub t0: f64,
    pub dt: f64,
    pub count: usize,
    /// Per frame, per body: the reference point (3) and the rotation as a unit
    /// quaternion (w, x, y, z).
    pub bodies: Vec<f64>,
    /// Per frame, per point: the position (3).
    pub points: Vec<f64>,
    /// Per frame, per plotted coordinate: its value.
    pub plotted: Vec<f64>,
    /// Each body's centre of mass in its own axes from the reference point
    /// (constant; read at the first frame).
    pub centres: Vec<Vector3<f64>>,
}

/// The frame times: `fps` per second of the run's span, capped at [`MAX_FRAMES`];
/// a run without dense output (thinned recording) gives its stored times.
fn frame_times<T: Real, const N: usize, const Q: usize>(
    traj: &Trajectory<T, N, Q>,
    fps: f64,
) -> (f64, f64, usize) {
    let times = traj.times();
    let t0 = times[0].to_f64();
    let t1 = times[times.len() - 1].to_f64();
    let wanted = if traj.segments().is_empty() {
        times.len()
    } else {
        ((t1 - t0) * fps).ceil() as usize + 1
    };
    let count = wanted.clamp(1, MAX_FRAMES);
    let dt = if count > 1 {
        (t1 - t0) / (count - 1) as f64
    } else {
        0.0
    };
    (t0, dt, count)
}

/// The state at a frame time: the dense output where there is one, else the
/// stored point nearest in time.
pub(super) fn state_at<T: Real, const N: usize, const Q: usize>(
    traj: &Trajectory<T, N, Q>,
    t: f64,
) -> SVector<T, Q> {
    if let Some((q, _)) = traj.state_at(T::lit(t)) {
        return q;
    }
    let times = traj.times();
    let i = times
        .partition_point(|&ti| ti.to_f64() < t)
        .min(times.len() - 1);
    let before_is_nearer = i > 0 && (t - times[i - 1].to_f64()) < (times[i].to_f64() - t);
    traj.positions()[if before_is_nearer { i - 1 } else { i }]
}

/// Samples the run.
///
/// # Errors
/// [`Error::NonFinitePose`] for a pose with a NaN or ∞.
pub(super) fn sample<T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q>>(
    sys: &S,
    traj: &Trajectory<T, N, Q>,
    fps: f64,
    plotted: &[usize],
) -> Result<Frames, Error> {
    let (t0, dt, count) = frame_times(traj, fps);
    let nb = S::BODIES.len();
    let np = S::POINTS.len();
    let mut bodies = vec![BodyPose::default(); nb];
    let mut points = vec![Vector3::zeros(); np];
    let mut frames = Frames {
        t0,
        dt,
        count,
        bodies: Vec::with_capacity(count * nb * 7),
        points: Vec::with_capacity(count * np * 3),
        plotted: Vec::with_capacity(count * plotted.len()),
        centres: Vec::new(),
    };
    for k in 0..count {
        let t = if k + 1 == count && count > 1 {
            traj.times()[traj.len() - 1].to_f64()
        } else {
            t0 + k as f64 * dt
        };
        let q = state_at(traj, t);
        sys.poses(&q, T::lit(t), &mut bodies, &mut points);
        for (i, pose) in bodies.iter().enumerate() {
            let pose = to_f64(pose);
            record_body(&mut frames, &pose, t, S::BODIES[i])?;
            if k == 0 {
                frames
                    .centres
                    .push(pose.rotation.transpose() * (pose.centre - pose.origin));
            }
        }
        for (i, p) in points.iter().enumerate() {
            let p = p.map(|x| x.to_f64());
            finite(p.iter(), t, S::POINTS[i])?;
            frames.points.extend(p.iter());
        }
        frames
            .plotted
            .extend(plotted.iter().map(|&j| q[j].to_f64()));
    }
    Ok(frames)
}

pub(super) fn to_f64<T: Real>(pose: &BodyPose<T>) -> BodyPose<f64> {
    BodyPose {
        origin: pose.origin.map(|x| x.to_f64()),
        centre: pose.centre.map(|x| x.to_f64()),
        rotation: pose.rotation.map(|x| x.to_f64()),
    }
}

/// Appends a body's reference point and rotation (as a quaternion: four
/// numbers for nine, and one the page can interpolate).
fn record_body(frames: &mut Frames, pose: &BodyPose<f64>, t: f64, name: &str) -> Result<(), Error> {
    let all = pose
        .origin
        .iter()
        .chain(pose.centre.iter())
        .chain(pose.rotation.iter());
    finite(all, t, name)?;
    let rotation = Rotation3::from_matrix(&pose.rotation);
    let q = UnitQuaternion::from_rotation_matrix(&rotation);
    frames.bodies.extend(pose.origin.iter());
    frames.bodies.extend([q.w, q.i, q.j, q.k]);
    Ok(())
}

fn finite<'a>(mut values: impl Iterator<Item = &'a f64>, t: f64, name: &str) -> Result<(), Error> {
    if values.all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinitePose {
            t,
            name: name.to_string(),
        })
    }
}
