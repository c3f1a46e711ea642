//! The humanoid-like spatial tree of `hunt_big_humanoid` with a floating base (test
//! `floating_humanoid` and bench `hunt_big`): the torso on a free joint instead of a
//! spherical joint on a stand, 33 degrees of freedom; the same head, arms and legs,
//! outputs and generated inverse dynamics.

use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[mechanism(spatial, inverse_dynamics)]
#[gravity(0.0, 0.0, -g)]
#[body(torso, joint = free(bx, by, bz, t1, t2, t3), at = [0.0, 0.0, 1.0], com = [0.0, 0.01, 0.25],
       mass = 20.0, inertia = [[0.6, 0.01, 0.02], [0.01, 0.5, 0.03], [0.02, 0.03, 0.2]])]
#[body(head, parent = torso, joint = spherical(h1, h2, h3), at = [0.0, 0.0, 0.5],
       com = [0.01, 0.0, 0.1], mass = 5.0, inertia = diag(0.03, 0.03, 0.02))]
#[body(arm_l, parent = torso, joint = spherical(sl1, sl2, sl3), at = [0.0, 0.2, 0.45],
       com = [0.0, 0.02, -0.15], mass = 2.0, inertia = diag(0.02, 0.02, 0.004))]
#[body(fore_l, parent = arm_l, joint = revolute(el, y), at = [0.0, 0.0, -0.3],
       com = [0.0, 0.0, -0.12], mass = 1.2, inertia = diag(0.01, 0.01, 0.002))]
#[body(hand_l, parent = fore_l, joint = universal(wl1, wl2), at = [0.0, 0.0, -0.25],
       com = [0.01, 0.0, -0.05], mass = 0.4, inertia = diag(0.001, 0.0012, 0.0005))]
#[body(arm_r, parent = torso, joint = spherical(sr1, sr2, sr3), at = [0.0, -0.2, 0.45],
       com = [0.0, -0.02, -0.15], mass = 2.0, inertia = diag(0.02, 0.02, 0.004))]
#[body(fore_r, parent = arm_r, joint = revolute(er, y), at = [0.0, 0.0, -0.3],
       com = [0.0, 0.0, -0.12], mass = 1.2, inertia = diag(0.01, 0.01, 0.002))]
#[body(hand_r, parent = fore_r, joint = universal(wr1, wr2), at = [0.0, 0.0, -0.25],
       com = [0.01, 0.0, -0.05], mass = 0.4, inertia = diag(0.001, 0.0012, 0.0005))]
#[body(thigh_l, parent = torso, joint = spherical(hl1, hl2, hl3), at = [0.0, 0.1, -0.05],
       com = [0.0, 0.0, -0.2], mass = 8.0, inertia = diag(0.15, 0.15, 0.03))]
#[body(shank_l, parent = thigh_l, joint = revolute(kl, y), at = [0.0, 0.0, -0.45],
       com = [0.0, 0.0, -0.2], mass = 3.5, inertia = diag(0.05, 0.05, 0.006))]
#[body(foot_l, parent = shank_l, joint = universal(al1, al2), at = [0.0, 0.0, -0.42],
       com = [0.05, 0.0, -0.04], mass = 1.0, inertia = diag(0.002, 0.005, 0.005))]
#[body(thigh_r, parent = torso, joint = spherical(hr1, hr2, hr3), at = [0.0, -0.1, -0.05],
       com = [0.0, 0.0, -0.2], mass = 8.0, inertia = diag(0.15, 0.15, 0.03))]
#[body(shank_r, parent = thigh_r, joint = revolute(kr, y), at = [0.0, 0.0, -0.45],
       com = [0.0, 0.0, -0.2], mass = 3.5, inertia = diag(0.05, 0.05, 0.006))]
#[body(foot_r, parent = shank_r, joint = universal(ar1, ar2), at = [0.0, 0.0, -0.42],
       com = [0.05, 0.0, -0.04], mass = 1.0, inertia = diag(0.002, 0.005, 0.005))]
#[output(tip = position(hand_l, [0.0, 0.0, -0.1]), tip_v = velocity(hand_l, [0.0, 0.0, -0.1]),
         tip_a = acceleration(hand_l, [0.0, 0.0, -0.1]), toe_v = velocity(foot_r, [0.1, 0.0, -0.05]),
         foot_w = angular_velocity(foot_r), head_alpha = angular_acceleration(head))]
pub struct FloatingHumanoid {
    pub g: f64,
}
