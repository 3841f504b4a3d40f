// Motor panels: a robot whose script called addGUI(title) gets a lil-gui panel with one
// slider per motor (its name, else its index); in a controller's view every robot with
// motors does (titled by its name, else its id), the panels closed when there are more
// than OPEN_AT_MOST. Where the page may steer the robot (a controller, on its own robot or
// a shared one) the sliders move the motors on the server, so every viewer sees it;
// elsewhere the panel follows the frames, read-only. The panels stack in one column (lil-gui
// would place each at the same corner, over each other). "Get gesture" shows the
// setAngles(...) call for the current pose.

import GUI from 'lil-gui';

const UNLIMITED = Math.PI;   // the slider range of an unlimited motor
const OPEN_AT_MOST = 2;      // panels shown open; more are closed (a title bar each)

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
	// every: a panel for every robot with motors (a controller's view), not only addGUI's;
	// container: where the panels stack.
	constructor(tree, { editable, setAngle, showGesture, guiFor = () => null, every = false, container }) {
		this.tree = tree;
		this.every = every;
		this.container = container;
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

	// Rebuild panels after structural changes (at most once per animation frame).
	step() {
		if (this.stale) this.rebuild();
	}

	// The sliders show the angles of the picture just drawn: refreshed with every picture,
	// not every animation frame (on a page drawing two pictures a second, two hands'
	// 40 sliders refreshed 60 times a second: its renderer spent 40 % of a core outside
	// JavaScript, in style, layout and paint among others; 23 % refreshed with pictures).
	show() {
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
		const robots = [...this.tree.objects.values()].filter((object) => this.hasPanel(object.userData.node));
		for (const robot of robots) this.build(robot, robots.length > OPEN_AT_MOST);
	}

	hasPanel(node) {
		if (node.type === 'Slot' || node.parent) return false;
		return node.gui != null || (this.every && (node.motors?.length ?? 0) > 0);
	}

	build(robot, closed) {
		const node = robot.userData.node;
		const title = node.gui || node.name || robot.name;
		const owned = this.guiFor(robot.name);
		const gui = owned ?? new GUI({ title, container: this.container });
		if (owned) gui.title(title);
		else if (closed) gui.close();
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
