// Motor panels: a robot whose script called addGUI(title) gets a lil-gui panel with one
// slider per motor (its name, else its index). Where the page may steer the robot (a
// controller, on its own robot or a shared one) the sliders move the motors on the server,
// so every viewer sees it; elsewhere the panel follows the frames, read-only.
// "Get gesture" shows the setAngles(...) call for the current pose.

import GUI from 'lil-gui';

const UNLIMITED = Math.PI;   // the slider range of an unlimited motor

function limit(value, fallback) {
	return typeof value === 'number' ? value : fallback;
}

// The motor objects of a robot in index order, as the server lists them.
export function motorsOf(robot, objects) {
	return (robot.userData.node.motors ?? []).map((id) => objects.get(id)).filter(Boolean);
}

export class MotorPanels {
	// editable(robotNode): may this page steer that robot? guiFor(robotId): a panel the
	// page already made for that robot (the JavaScript client's robot.gui), filled here
	// instead of a new one.
	constructor(tree, { editable, setAngle, showGesture, guiFor = () => null }) {
		this.tree = tree;
		this.guiFor = guiFor;
		this.editable = editable;
		this.setAngle = setAngle;
		this.showGesture = showGesture;
		this.panels = new Map();   // robot id -> {gui, sliders: Map motor object -> slider, values}
		this.stale = false;
		const refresh = () => { this.stale = true; };
		tree.on('added', refresh);
		tree.on('removed', refresh);
		const shaping = ['gui', 'motors', 'name', 'shared'];
		tree.on('changed', (object, fields) => { if (shaping.some((key) => key in fields)) refresh(); });
	}

	// Rebuild panels after structural changes (at most once per rendered frame).
	step() {
		if (this.stale) this.rebuild();
		for (const panel of this.panels.values()) for (const [object, slider] of panel.sliders) {
			const angle = object.userData.node.angle;
			if (!slider.dragging && panel.values[object.name] !== angle) {
				panel.values[object.name] = angle;
				slider.updateDisplay();
			}
		}
	}

	rebuild() {
		this.stale = false;
		for (const { gui, owned } of this.panels.values()) {
			if (owned) for (const controller of gui.controllersRecursive()) controller.destroy();
			else gui.destroy();
		}
		this.panels.clear();
		for (const object of this.tree.objects.values()) {
			const node = object.userData.node;
			if (node.type !== 'Slot' && node.gui != null && !node.parent) this.build(object);
		}
	}

	build(robot) {
		const title = robot.userData.node.gui || 'Robot';
		const owned = this.guiFor(robot.name);
		const gui = owned ?? new GUI({ title });
		if (owned) gui.title(title);
		const values = {}, sliders = new Map();
		const editable = this.editable(robot.userData.node);
		motorsOf(robot, this.tree.objects).forEach((motor, index) => {
			const node = motor.userData.node;
			values[motor.name] = node.angle;
			const slider = gui.add(values, motor.name, limit(node.min, -UNLIMITED), limit(node.max, UNLIMITED), 0.01)
				.name(node.name ?? String(index));
			if (editable) {
				slider.onChange((angle) => { slider.dragging = true; this.setAngle(motor.name, angle); });
				slider.onFinishChange(() => { slider.dragging = false; });
			} else slider.disable();
			sliders.set(motor, slider);
		});
		gui.add({ gesture: () => this.showGesture(gesture(robot, this.tree.objects)) }, 'gesture')
			.name('Get gesture');
		this.panels.set(robot.name, { gui, sliders, values, owned });
	}
}

// The setAngles(...) call that puts a robot in its current pose.
export function gesture(robot, objects) {
	const angles = motorsOf(robot, objects).map((motor) => Number(motor.userData.node.angle.toFixed(2)));
	return `setAngles( ${angles.join(', ')} );`;
}
