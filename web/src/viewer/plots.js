// Plots of what the frames carry, drawn with uPlot (npm: made for streaming time series):
// every watched sensor's distance, touch and force, and every motor's angle, any of them
// on one chart against the scene's time, listed by name ("hand · thumb angle") with a filter
// box; a robot's motors are plotted until someone ticks a series. Live, the chart shows
// the last WINDOW seconds; over a recording (cursor(): the player's time) the whole
// recording (preload: replay.js reads every tick of it), with a line where the player
// stands. CSV gives the chart's time window as a file.

import uPlot from 'uplot';
import { eachAngle } from '/client/pose.js';

const WINDOW = 30;          // s of scene time shown live
const KEEP = 20000;         // samples kept a series live (older ones go)
const KEEP_RECORDED = 360000;  // over a recording: an hour at 60 Hz
const DEFAULT_MOTORS = 8;   // plotted at first: a robot's first motors
const DRAW_EVERY = 100;     // ms between redraws (a chart redrawn at 60 Hz costs the picture)
const READINGS = ['distance', 'touch', 'force'];
const COLORS = ['#d62728', '#1f77b4', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
const STYLESHEET = '/vendor/uplot/dist/uPlot.min.css';

export class Plots {
	// motorsOf(robotId): its motor ids in order; cursor(): the player's scene time (a
	// recording) or null; span(): the recording's [start, end] in scene time (null live)
	// heat(on): the heat map on the robots (heat.js) on or off; named(id): what a person
	// calls a sensor or motor ("robot · motor", by names where they have them)
	constructor({ motorsOf, cursor = () => null, span = () => null, heat = () => {}, named = (id) => id }) {
		this.motorsOf = motorsOf;
		this.named = named;
		this.heat = heat;
		this.cursor = cursor;
		this.span = span;
		this.series = new Map();   // name -> Map(time -> value)
		this.chosen = [];          // names plotted, in order
		this.element = null;
		this.plot = null;
		this.dirty = false;
		this.listed = 0;
		this.touched = false;      // until someone ticks a series, a robot's motors are plotted
		this.motorLists = new Map();   // robot id -> motor ids, as the messages plotted said
		this.latest = null;        // the newest frame's time
	}

	// Called with every message the viewer gets.
	receive(message) {
		if (message.op === 'snapshot' && this.cursor() === null) this.clear();
		this.take(message);
	}

	// Ticks of a recording ([time, messages] each), all of them whatever the player shows
	// (a sample at a time already had is the same sample).
	preload(ticks) {
		for (const [, messages] of ticks) for (const message of messages) this.take(message);
	}

	take(message) {
		const nodes = message.op === 'snapshot' || message.op === 'added' ? message.nodes : [];
		for (const node of nodes) if (node.motors) this.motorLists.set(node.id, node.motors);
		for (const [id, fields] of Object.entries(message.updates ?? {})) {
			if (fields.motors) this.motorLists.set(id, fields.motors);
		}
		if (message.op !== 'frame') return;
		const at = message.time;
		this.latest = Math.max(this.latest ?? at, at);
		for (const [sensor, reading] of Object.entries(message.sensors ?? {})) {
			for (const field of READINGS) {
				const value = reading[field];
				if (value !== undefined) this.add(`${sensor} ${field}`, at, typeof value === 'number' ? value : null);
			}
		}
		const motorsOf = (robot) => this.motorLists.get(robot) ?? this.motorsOf(robot);
		for (const [motor, angle] of eachAngle(message.angles, motorsOf)) this.add(`${motor} angle`, at, angle);
	}

	add(name, at, value) {
		let samples = this.series.get(name);
		if (!samples) this.series.set(name, samples = new Map());
		samples.set(at, value);
		if (samples.size > (this.cursor() === null ? KEEP : KEEP_RECORDED)) samples.delete(samples.keys().next().value);
		this.dirty = true;
	}

	clear() {
		for (const samples of this.series.values()) samples.clear();
		this.dirty = true;
	}

	// The panel: a list of series to tick, the chart and CSV.
	open() {
		if (this.element) return (this.element.hidden = !this.element.hidden);
		if (![...document.styleSheets].some((sheet) => sheet.href?.endsWith(STYLESHEET))) {
			document.head.append(Object.assign(document.createElement('link'), { rel: 'stylesheet', href: STYLESHEET }));
		}
		this.element = Object.assign(document.createElement('div'), { id: 'plots', className: 'plots' });
		this.filter = Object.assign(document.createElement('input'), {
			type: 'search', className: 'series-filter', placeholder: 'filter: thumb, angle, force…' });
		this.filter.addEventListener('input', () => this.listSeries(true));
		this.list = Object.assign(document.createElement('div'), { className: 'series' });
		this.chart = document.createElement('div');
		const csv = Object.assign(document.createElement('button'), { textContent: 'CSV', title: 'the chart\'s time window as a CSV file' });
		csv.addEventListener('click', () => this.download());
		const heat = Object.assign(document.createElement('input'), { type: 'checkbox', id: 'heat' });
		heat.addEventListener('change', () => this.heat(heat.checked));
		const heatLabel = Object.assign(document.createElement('label'), { title: 'parts glow red with the force on them, sensor pads with their touch' });
		heatLabel.append(heat, ' heat map on the robots');
		this.element.append(this.filter, this.list, this.chart, csv, heatLabel);
		document.body.append(this.element);
		setInterval(() => this.draw(), DRAW_EVERY);
		this.rebuild();
	}

	choose(name, on = true) {
		this.touched = true;
		this.chosen = on ? [...new Set([...this.chosen, name])] : this.chosen.filter((n) => n !== name);
		this.rebuild();
	}

	rebuild() {
		this.plot?.destroy();
		this.plot = new uPlot({
			width: 460, height: 220, legend: { live: false },
			scales: { x: { time: false, range: (u, min, max) => this.span() ?? [min, max] } },
			series: [{ label: 's' }, ...this.chosen.map((name, k) => ({ label: this.label(name), stroke: COLORS[k % COLORS.length], spanGaps: true }))],
			axes: [this.timeAxis(), {}],
			hooks: { draw: [(u) => this.drawCursor(u)] },
		}, this.data(), this.chart);
		this.listSeries(true);
	}

	// Over a recording the axis counts from its start, as the player's timeline does (the
	// data stay in scene time: the CSV's too); live, the scene's time.
	timeAxis() {
		const span = this.span();
		if (!span) return { label: 'scene time (s)' };
		return {
			label: 'time in the recording (s)',
			// ticks at round times of the recording (uPlot's increment), not of the scene
			splits: (u, axis, min, max, increment) => {
				const ticks = [];
				for (let at = span[0] + Math.ceil((min - span[0]) / increment - 1e-9) * increment; at <= max + 1e-9; at += increment) ticks.push(at);
				return ticks;
			},
			values: (u, splits) => splits.map((at) => +(at - span[0]).toFixed(3)),
		};
	}

	// The ticks: one per series seen so far (new ones appear as frames bring them).
	listSeries(force = false) {
		if (!force && this.series.size === this.listed) return;
		this.listed = this.series.size;
		const first = this.touched ? [] : this.firstChoice();
		if (first.length && first.join() !== this.chosen.join()) {
			this.chosen = first;
			return this.rebuild();
		}
		const wanted = (this.filter?.value ?? '').trim().toLowerCase();
		const shown = [...this.series.keys()].map((name) => [this.label(name), name])
			.filter(([label]) => label.toLowerCase().includes(wanted))
			.sort(([a], [b]) => a.localeCompare(b, undefined, { numeric: true }));
		this.list.replaceChildren(...shown.map(([text, name]) => {
			const box = Object.assign(document.createElement('input'), { type: 'checkbox', checked: this.chosen.includes(name) });
			box.addEventListener('change', () => this.choose(name, box.checked));
			const label = Object.assign(document.createElement('label'), { title: name });
			label.append(box, ` ${text}`);
			return label;
		}));
	}

	// What is plotted before anyone chooses: the first robot's motors (robots in the order
	// the scene made them), else the first sensor's distance.
	firstChoice() {
		for (const motors of this.motorLists.values()) {
			const angles = motors.map((id) => `${id} angle`).filter((name) => this.series.has(name));
			if (angles.length) return angles.slice(0, DEFAULT_MOTORS);
		}
		const distance = [...this.series.keys()].sort().find((name) => name.endsWith(' distance'));
		return distance ? [distance] : [];
	}

	// A series' name as a person reads it: "<what> <field>", the id named (named()).
	label(name) {
		const cut = name.lastIndexOf(' ');
		return `${this.named(name.slice(0, cut))} ${name.slice(cut + 1)}`;
	}

	// [times, ...values] for uPlot: every time any chosen series has, in order, and the
	// latest time (live) or the recording's end, within the window. Frames carry changes
	// only, so a value holds until the next one: each series is carried forward (a motor
	// that stopped is a flat line to the end, not a line that stops where it last moved).
	data() {
		const times = new Set();
		for (const name of this.chosen) for (const at of this.series.get(name)?.keys() ?? []) times.add(at);
		const end = this.span()?.[1] ?? this.latest;
		if (times.size && end !== null) times.add(end);
		const ordered = [...times].sort((a, b) => a - b);
		const columns = this.chosen.map((name) => {
			const samples = this.series.get(name) ?? new Map();
			let held = null;
			return ordered.map((at) => (held = samples.has(at) ? samples.get(at) : held));
		});
		const from = this.cursor() === null && ordered.length
			? ordered.findIndex((at) => at >= ordered[ordered.length - 1] - WINDOW) : 0;
		return [ordered.slice(from), ...columns.map((column) => column.slice(from))];
	}

	draw() {
		if (!this.element || this.element.hidden) return;
		this.listSeries();
		if (this.dirty) {
			this.dirty = false;
			this.plot.setData(this.data());
		} else if (this.cursor() !== null) {
			this.plot.redraw(false, false);   // the player's line moves
		}
	}

	drawCursor(u) {
		const at = this.cursor();
		if (at === null) return;
		const x = u.valToPos(at, 'x', true);
		const { ctx, bbox } = u;
		ctx.save();
		ctx.strokeStyle = '#333';
		ctx.beginPath();
		ctx.moveTo(x, bbox.top);
		ctx.lineTo(x, bbox.top + bbox.height);
		ctx.stroke();
		ctx.restore();
	}

	// The chart's visible time window of the chosen series as CSV text.
	csv() {
		const [times, ...columns] = this.data();
		const { min = -Infinity, max = Infinity } = this.plot?.scales.x ?? {};
		const rows = [['time', ...this.chosen].join(',')];
		times.forEach((at, k) => {
			if (at >= min && at <= max) rows.push([at, ...columns.map((column) => column[k] ?? '')].join(','));
		});
		return `${rows.join('\n')}\n`;
	}

	download() {
		const link = Object.assign(document.createElement('a'), {
			href: URL.createObjectURL(new Blob([this.csv()], { type: 'text/csv' })), download: 'readings.csv' });
		link.click();
		setTimeout(() => URL.revokeObjectURL(link.href), 0);
	}
}
