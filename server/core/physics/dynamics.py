"""Dynamic mode: gravity, masses, torque-limited motors, mounts and stepping, in Bullet.

A scene is kinematic (1.0's behaviour: motors jump to their angles, nothing falls, contacts
are reported, not resolved) or dynamic. In dynamic mode the same compiled trees
(:mod:`.articulation`) are Bullet multibodies with mass: a robot's base floats, held where
the script puts it by a fixed constraint of bounded force (its *mount*: moving it drags
the hand smoothly, so a hand carries what it holds); any other tree is a free body that
falls, unless it is static; every motor drives its joint toward its target with bounded
torque (``POSITION_CONTROL``), so a finger stopped by an object stays where it stopped.

The scene's options and their defaults, and why, are in :mod:`.settings`.

Nothing sleeps (Bullet's deactivation of bodies still for 2 s) in a world of up to
SLEEP_CROWD free bodies: with sleeping the Box and Blocks baseline (150 blocks) moved
fewer blocks with every hand. Past it, resting free bodies sleep: a pile of 500 balls
never came to rest without (its jitter kept every ball moving), and with it settled in
seconds and cost nearly nothing. A sleeper is woken when it is put somewhere, and every
one when a free body goes (it may have held some up). Past resting.CROWD free bodies,
a single one at rest far from anything moving is held still on its own (:mod:`.resting`):
Bullet sleeps a touching heap only as a whole. Every tree is a multibody: single bodies as
Bullet rigid bodies solve faster but held the grasp task's objects less well.
"""

from __future__ import annotations

import math
import time
from typing import Any, Callable, Sequence

from ..kit.math3d import ORIGIN, Pose, Vec3, between, compose
from .articulation import NO_POSE, Articulation
from .geometry import centroid, volume
from .resting import Resting
from .settings import Physics
from .warm_start import enable as warm_start

MAX_STEPS_PER_TICK = 2  # × substeps: a late tick catches up this far, no further (a scene
# that cannot keep up runs slower than real time rather than sending fewer, larger steps)
# CPU-seconds of physics steps a tick may take. Past it the tick's other steps are left
# out (the world runs slower than real time), and a single step that costs more gets
# fewer solver iterations from then on (given back as steps get cheap again): a pile of
# 2 000 balls, a tower of 300 boxes or 500 iterations of 20 substeps keep ticking rather
# than take seconds a tick. CPU time, not the wall clock: a loaded machine's waits are no
# work of the scene's, and cut nothing from it.
STEP_BUDGET = 0.04
# Figures without a part, in Bullet's units (kg × unit³ in SI: the same share of a 1.0 hand
# at any unit; Bullet only needs some, and a link a million times lighter than its
# neighbours left a motor pushing through a wall)
BETWEEN_MASS = 0.1  # a link that carries no part (where two joints meet), the least a part weighs
# What a robot's mount pulls with (its constraint's bound): far past the weight of a 1 kg
# robot at any unit from 1.5 cm up (8.7 kN at the default unit)
MOUNT_FORCE = 1e9
MOUNT_MASS = 1.0  # a robot base without a part of its own
UNBOUNDED_SPEED = 1e30  # Bullet's motor speed bound for none (it keeps the last one set)
SHAPELESS_INERTIA = 1e-3  # of a base or link without a part (× unit⁵: kg·m²)
SPINNING, ROLLING = 0.2, 0.002  # of a free body's lateral friction (robots and static
# bodies carry none: Bullet adds both bodies' shares, so a free body's contact with a finger
# or a table gets 0.2 and 0.002 of the two frictions' product, and contacts of fingers with
# fingers, palms or the ground carry no turning friction, which the solver would pay for)
BREAKING_THRESHOLD = 0.02  # Bullet's own: contacts persist while resting (kinematic: 0.0005)
# What a motor drives with unless setMaxTorque (or a robot file's effort) says otherwise
# (N·m): a small servo's, enough for every bundled hand at the default unit to hold its
# fingers level and close on a ball of its own size (about 50 g) under 9.81 m/s². One
# figure for every motor: the drawn sizes of the 1.0 motors are pictures, not actuators (a
# round finger's spread motor is drawn with size 0), so a designer gives real actuators
# their torques.
DEFAULT_MAX_TORQUE = 0.2
DEFAULT_MAX_FORCE = 20.0  # N: a sliding motor's bound (a small linear actuator's)
SLEEP_CROWD = 256  # free bodies past which resting ones sleep



SOLIDS_KEPT = 4096  # shapes' volumes and centres a process keeps (Dynamics._solid)
_SOLIDS: dict[str, tuple[float, Vec3]] = {}


class Dynamics:
    """The dynamic side of one PyBullet client (``pybullet`` is the module, ``client`` its id)."""

    def __init__(self, pybullet: Any, client: int, physics: Physics) -> None:
        self.p, self.client, self.physics = pybullet, client, physics
        self._debt = 0.0  # seconds not yet stepped
        self.steps = 0  # physics steps taken
        self._mounts: dict[int, Pose] = {}  # mount constraint -> where it is
        self._glides: dict[int, Pose] = {}  # mount constraint -> where it goes over the next steps
        self._moving: set[int] = set()  # bodies with parts that move (the solver's tolerance)
        self._speed_bound: set[int] = set()  # bodies with a motor whose speed is bounded
        self.iterations = physics.solverIterations  # what steps use now (STEP_BUDGET)
        self.held_back = 0  # steps the last advance left out (STEP_BUDGET)
        self.stepping = 0.0  # clock-seconds Bullet's steps took in the last advance (exact: 0, untimed)
        self.clock: Callable[[], float] = time.thread_time  # the CPU-seconds steps cost
        self._free: set[int] = set()  # free bodies (SLEEP_CROWD)
        self.sleeping = False  # resting free bodies sleep (more than SLEEP_CROWD of them)
        self._wake_all = False  # before the next step (a free body went)
        self.units = physics.bullet
        self.resting = Resting(pybullet, client, physics.unit, self.units.acceleration(physics.gravity))
        self.woke = False  # the last steps' review let resting bodies move again
        pybullet.setGravity(0, -self.units.acceleration(physics.gravity), 0, physicsClientId=client)
        pybullet.setPhysicsEngineParameter(fixedTimeStep=physics.step,
                                           numSolverIterations=physics.solverIterations,
                                           contactBreakingThreshold=BREAKING_THRESHOLD,
                                           physicsClientId=client)
        # False when off, or when this PyBullet can't (warm_start logs which)
        self.warm_started = bool(physics.warmStart) and warm_start(pybullet, client, physics.warmStart)

    # --- building ----------------------------------------------------------------------

    def masses(self, tree: Articulation) -> tuple[float, list[float]]:
        """The base's mass and every link's in Bullet's units, as :func:`tree_masses` weighs
        them; 0 for the base of a static tree (Bullet: fixed)."""
        base, links = tree_masses(tree, self.physics.density, self._volume, self.units.unit)
        if tree.base_geometry is None and tree.links:
            # what hangs on a base reaches its mount only through the solver: on a base of
            # MOUNT_MASS, 155 times lighter than the block a slider held up, the mount sank
            # by 12 % of the block's size; as heavy as what hangs on it, the base holds still
            base = max(base, sum(links))
        per = self.units.mass
        return (0.0 if tree.static else base / per), [mass / per for mass in links]

    def _volume(self, geometry: dict[str, Any]) -> float:
        return self._solid(geometry)[0]

    def _solid(self, geometry: dict[str, Any]) -> tuple[float, Vec3]:
        """Volume and centre of mass (in the part's frame) of a geometry, kept by shape for
        the process: a world rebuilt (every restoreState) weighs the same shapes again."""
        key = repr(sorted((k, v) for k, v in geometry.items() if k not in ("color", "edges")))
        solid = _SOLIDS.get(key)
        if solid is None:
            if len(_SOLIDS) >= SOLIDS_KEPT:
                _SOLIDS.clear()
            solid = _SOLIDS[key] = (volume(geometry), centroid(geometry))
        return solid

    def _load_inertia(self, tree: Articulation) -> float:
        """A part-less base's inertia, in Bullet's units: that of its links' masses about
        it at rest. The mount holds the base's turn only through the solver, and a base of
        a small ball's inertia let a motor's 0.1 kg arm turn it 0.7 rad (the motor reading
        no torque); as hard to turn as its load, it holds to 1e-3 rad. The load lies at its
        links' centres of mass (measured to their parts' frames, a finger's at its joint, an
        arm on a motor weighed nothing, and its base turned under it)."""
        _, masses = self.masses(tree)
        _, centres = self.centres(tree)
        poses: list[Pose] = []
        for link in tree.links:
            poses.append(compose(NO_POSE if link.parent < 0 else poses[link.parent], link.origin))
        reach = [math.dist(ORIGIN, compose(compose(pose, link.shape), (centre, NO_POSE[1]))[0])
                 for pose, link, centre in zip(poses, tree.links, centres)]
        return max(SHAPELESS_INERTIA, sum(m * r * r for m, r in zip(masses, reach)))

    def centres(self, tree: Articulation) -> tuple[Vec3, list[Vec3]]:
        """Where the base's and each link's centre of mass lies in its part's frame (a
        finger's lies halfway up it, not at its joint: gravity turns it)."""
        def of(geometry: dict[str, Any] | None) -> Vec3:
            return ORIGIN if geometry is None else self._solid(geometry)[1]
        return of(tree.base_geometry), [link.centre if link.centre is not None else
                                        of(link.geometry) for link in tree.links]

    def made(self, body: int, tree: Articulation, base_pose: Pose,
             joint_links: Sequence[int], mount_pose: Pose | None = None) -> int | None:
        """Finish a tree built as ``body``: its friction, joint limits and motors (driven by
        :meth:`drive` only), and for a robot its mount (the constraint's id), at
        ``mount_pose`` (None: where its base is)."""
        p, client = self.p, self.client
        self._surface(body, tree)
        self._note_moving(body, tree)
        # Bullet gives a link without a shape no inertia at all, and a joint between two
        # such turns the whole motor's torque into spin of nothing: a motor then holds any
        # load whatever its torque. They get that of a small ball of their mass.
        shapeless = ([-1] if tree.base_geometry is None and not tree.static else []) + \
            [k for k, link in enumerate(tree.links) if link.geometry is None]
        for link in shapeless:
            p.changeDynamics(body, link, localInertiaDiagonal=(SHAPELESS_INERTIA,) * 3,
                             physicsClientId=client)
        if shapeless[:1] == [-1] and tree.links:  # (the base's, turned by what hangs on it)
            p.changeDynamics(body, -1, localInertiaDiagonal=(self._load_inertia(tree),) * 3,
                             physicsClientId=client)
        for k, link in enumerate(tree.links):  # a robot file's own inertia (else the shape's)
            if link.inertia is not None:  # (kg·scene unit²)
                p.changeDynamics(body, k, localInertiaDiagonal=[max(i / self.units.mass, 1e-12)
                                                                for i in link.inertia],
                                 physicsClientId=client)
        for k in joint_links:
            joint = tree.links[k].joint
            if math.isfinite(joint.lower) and math.isfinite(joint.upper):  # type: ignore[union-attr]
                p.changeDynamics(body, k, jointLowerLimit=joint.lower,  # type: ignore[union-attr]
                                 jointUpperLimit=joint.upper, physicsClientId=client)  # type: ignore[union-attr]
        if joint_links:  # Bullet's own velocity motors would hold every joint still
            p.setJointMotorControlArray(body, list(joint_links), p.VELOCITY_CONTROL,
                                        forces=[0.0] * len(joint_links), physicsClientId=client)
        if not tree.mounted or tree.static:
            if body in self._moving:  # a free body
                self._free.add(body)
                self._doze(body)
                if not tree.links:
                    self.resting.add(body)
            return None
        mount = p.createConstraint(body, -1, -1, -1, p.JOINT_FIXED, (0, 0, 0), (0, 0, 0),
                                   base_pose[0], childFrameOrientation=base_pose[1],
                                   physicsClientId=client)
        self._put(mount, mount_pose or base_pose)  # (Bullet's own bound lets a heavy hand sink)
        return mount

    def _note_moving(self, body: int, tree: Articulation) -> None:
        """Note a tree with parts that moves (the solver's tolerance is kept from then on)."""
        if not tree.static and (tree.base_geometry is not None or
                                any(link.geometry is not None for link in tree.links)):
            self._moving.add(body)
            self._tolerate()

    def _tolerate(self) -> None:
        """Bullet's residual threshold (the square of a row's velocity change, in Bullet's
        units) from ``solverTolerance``: a share of the speed gravity gives in a step
        (nothing moving: every iteration)."""
        speed = self.physics.solverTolerance * abs(self.units.acceleration(self.physics.gravity)) \
            * self.physics.step if self._moving else 0.0
        self.p.setPhysicsEngineParameter(solverResidualThreshold=speed * speed,
                                         physicsClientId=self.client)

    def _surface(self, body: int, tree: Articulation) -> None:
        """Every link's friction (turning friction only on a free body's)."""
        p, client = self.p, self.client
        turning = 0.0 if tree.mounted or tree.static else 1.0
        frictions = {-1: tree.base_friction, **{k: link.friction for k, link in enumerate(tree.links)}}
        for link, given in frictions.items():
            mu = self.physics.friction if given is None else given
            p.changeDynamics(body, link, lateralFriction=mu, spinningFriction=turning * SPINNING * mu,
                             rollingFriction=turning * ROLLING * mu, frictionAnchor=1,
                             physicsClientId=client)

    # --- driving -----------------------------------------------------------------------

    def drive(self, body: int, joint_links: Sequence[int], targets: list[float],
              torques: list[float], speeds: list[float], sliding: Sequence[bool]) -> None:
        """Every motor of a tree toward its target, with at most its torque (N·m; a
        sliding joint's: its force, N) and no faster than its speed (rad/s, a sliding
        joint's scene units/s, which are Bullet's; inf: no limit)."""
        p, torque, force = self.p, self.units.torque, self.units.force
        bounds = [bound / (force if slides else torque) for bound, slides in zip(torques, sliding)]
        p.setJointMotorControlArray(body, list(joint_links), p.POSITION_CONTROL,
                                    targetPositions=targets, forces=bounds, physicsClientId=self.client)
        bounded = any(math.isfinite(speed) for speed in speeds)
        if not bounded and body not in self._speed_bound:
            return
        # the array call sets no speed bound, and keeps one set before: each joint's own call
        for link, target, bound, speed in zip(joint_links, targets, bounds, speeds):
            p.setJointMotorControl2(body, link, p.POSITION_CONTROL, targetPosition=target, force=bound,
                                    maxVelocity=speed if math.isfinite(speed) else UNBOUNDED_SPEED,
                                    physicsClientId=self.client)
        (self._speed_bound.add if bounded else self._speed_bound.discard)(body)

    def mount(self, constraint: int, pose: Pose) -> None:
        """Move a robot's mount: it glides there over the steps of the next advance (a
        script's 60 moves a second are a path, not a staircase: a mount that jumped once a
        tick jerked what the hand held, and more so when a busy server took two ticks'
        steps at once), and its base follows, pulled with at most MOUNT_FORCE."""
        self._glides[constraint] = pose

    def place_mount(self, constraint: int, pose: Pose) -> None:
        """Put a robot's mount at ``pose`` at once, without a glide."""
        self._glides.pop(constraint, None)
        self._put(constraint, pose)

    def removed(self, body: int, mount: int | None) -> None:
        """A tree gone, with its mount (Bullet gives their ids to the next ones made)."""
        self._speed_bound.discard(body)
        self.resting.removed(body)
        if body in self._free:
            self._free.discard(body)
            self._wake_all = self.sleeping
            self._doze()
        if mount is not None:
            self._mounts.pop(mount, None)
            self._glides.pop(mount, None)
        if body in self._moving:
            self._moving.discard(body)
            self._tolerate()

    def _doze(self, new: int | None = None) -> None:
        """Let resting free bodies sleep once there are more than SLEEP_CROWD (``new``: a
        body just made), and none sleep again once there are fewer."""
        p = self.p
        wanted = len(self._free) > SLEEP_CROWD
        if wanted != self.sleeping:
            self.sleeping = wanted
            for body in self._free:
                self._activate(body, p.ACTIVATION_STATE_ENABLE_SLEEPING if wanted else
                               p.ACTIVATION_STATE_DISABLE_SLEEPING | p.ACTIVATION_STATE_WAKE_UP)
        elif wanted and new is not None:
            self._activate(new, p.ACTIVATION_STATE_ENABLE_SLEEPING)

    def _activate(self, body: int, state: int) -> None:
        self.p.changeDynamics(body, -1, activationState=state, physicsClientId=self.client)

    def _put(self, constraint: int, pose: Pose) -> None:
        self.p.changeConstraint(constraint, pose[0], pose[1], maxForce=MOUNT_FORCE,
                                physicsClientId=self.client)
        self._mounts[constraint] = pose

    def teleport(self, body: int, pose: Pose) -> None:
        """Put a free body at a pose, at rest (a script's setPosition of an object)."""
        self.resting.release(body)
        self.p.resetBasePositionAndOrientation(body, pose[0], pose[1], physicsClientId=self.client)
        self.p.resetBaseVelocity(body, (0, 0, 0), (0, 0, 0), physicsClientId=self.client)
        if self.sleeping and body in self._free:
            self._activate(body, self.p.ACTIVATION_STATE_WAKE_UP)

    def advance(self, seconds: float, still: bool = False, exact: bool = False) -> int:
        """Step the world through ``seconds`` (what is left over waits for the next call;
        a late tick catches up at most MAX_STEPS_PER_TICK ticks, and takes no more steps
        than STEP_BUDGET allows); the steps taken. ``still``: nothing moved in the last
        steps and nothing was changed since, so steps would change nothing either: they
        are counted, not taken (a settled heap of 2 000 sleeping balls still cost Bullet
        2.5 ms a step for its broadphase and islands). ``exact``: a script steps the
        scene and waits for it: every step, with every iteration, whatever they cost (a
        budget of CPU time made the same seeded grasp end differently on a busy machine)."""
        step = self.physics.step
        limit = MAX_STEPS_PER_TICK * self.physics.substeps
        self._debt = min(self._debt + seconds, limit * step)
        count = int(self._debt / step + 1e-9)
        self.held_back, self.stepping = 0, 0.0
        if not count:
            return 0
        self._debt -= count * step  # steps the budget leaves out are not owed later
        if still:
            return count
        # a mount sent where it is already (a script holding a wrist still, 60 times a
        # second) has nowhere to glide: five constraint updates a tick saved
        glides = [(c, self._mounts[c], pose) for c, pose in self._glides.items()
                  if self._mounts[c] != pose]
        self._glides.clear()
        if self._wake_all:
            for body in self._free:
                self._activate(body, self.p.ACTIVATION_STATE_WAKE_UP)
            self._wake_all = False
        spent, taken = 0.0, 0
        if exact:
            self._tune(0.0)  # the scene's own iterations again
        while taken < count and (exact or not taken or spent * (taken + 1) / taken <= STEP_BUDGET):
            taken += 1
            for constraint, start, end in glides:
                self._put(constraint, between(start, end, taken / count))
            if exact:  # every step is taken, whatever it costs: nothing to time
                self.p.stepSimulation(physicsClientId=self.client)
                continue
            started = self.clock()
            self.p.stepSimulation(physicsClientId=self.client)
            spent += self.clock() - started
        for constraint, _, end in glides if taken < count else ():
            self._put(constraint, end)
        if not exact:
            self._tune(spent / taken)
        self.stepping = spent
        self.held_back = count - taken
        self.steps += taken
        self.woke = self.resting.review(taken * step, self._moving - self.resting.free)
        return taken

    def _tune(self, per_step: float) -> None:
        """Fewer solver iterations when one step costs more than STEP_BUDGET; more again,
        up to the scene's own, when steps cost less than a quarter of it."""
        wanted = self.iterations
        if per_step > STEP_BUDGET:
            wanted = max(1, int(self.iterations * STEP_BUDGET / per_step * 0.8))
        elif per_step == 0.0:
            wanted = self.physics.solverIterations
        elif per_step < STEP_BUDGET / 4:
            wanted = min(self.physics.solverIterations, 2 * self.iterations)
        if wanted != self.iterations:
            self.iterations = wanted
            self.p.setPhysicsEngineParameter(numSolverIterations=wanted, physicsClientId=self.client)

    # --- reading -----------------------------------------------------------------------

    def base_pose(self, body: int) -> Pose:
        position, orientation = self.p.getBasePositionAndOrientation(body, physicsClientId=self.client)
        return tuple(position), tuple(orientation)

    def joint_angles(self, body: int, joint_links: Sequence[int]) -> list[float]:
        """The joints' real angles (radians; a sliding joint's length)."""
        states = self.p.getJointStates(body, list(joint_links), physicsClientId=self.client)
        return [state[0] for state in states]

    def joint_motion(self, body: int, joint_links: Sequence[int],
                     sliding: Sequence[bool]) -> tuple[list[float], list[float]]:
        """The joints' speeds (rad/s; a sliding joint's, scene units/s) and the torques their
        motors applied in the last step (N·m; a sliding joint's force, N): Bullet keeps
        both until the next step, so they are read when asked, not every tick."""
        states = self.p.getJointStates(body, list(joint_links), physicsClientId=self.client)
        torque, force = self.units.torque, self.units.force
        return ([state[1] for state in states],
                [state[3] * (force if slides else torque) for state, slides in zip(states, sliding)])


def tree_masses(tree: Articulation, density: float,
                volume_of: Callable[[dict[str, Any]], float] = volume,
                unit: float = 1.0) -> tuple[float, list[float]]:
    """The base's mass and every link's (kg) in a scene of ``unit`` metres per scene unit:
    a part's own (``setMass``), else its volume times ``density``; BETWEEN_MASS for a link
    without a part, MOUNT_MASS for a base without one (both in Bullet's units)."""
    per_mass = unit ** 3
    per_volume, least = density * per_mass, BETWEEN_MASS * per_mass

    def of(given: float | None, geometry: dict[str, Any] | None) -> float:
        if given is not None:
            return given
        return least if geometry is None else max(least, per_volume * volume_of(geometry))
    base = MOUNT_MASS * per_mass if tree.base_geometry is None else of(tree.base_mass, tree.base_geometry)
    return base, [of(link.mass, link.geometry) for link in tree.links]
