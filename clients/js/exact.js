// The exact form of every read: `await object.<read>Exact(…)` asks the server, which
// answers after every earlier request of this client (reads without the suffix return
// the mirror's value at once). READS is checked against protocol/api.json by a test.

import { fromWire } from './codec.js';

export const READS = Object.freeze({
	getAngle: 'number', getAngles: 'numbers', getPosition: 'point',
	getParts: 'refs', getMotors: 'refs', getSensors: 'refs',
	senseDistance: 'number', senseTouch: 'number', sensePosition: 'point',
	senseCollision: 'bool', senseObjects: 'ids', senseObject: 'bool',
	senseForce: 'number', senseContacts: 'contacts', getMaxTorque: 'number', getMaxSpeed: 'number',
	getTorque: 'number', getSpeed: 'number', getSpeeds: 'numbers', getTorques: 'numbers', getGripMap: 'gripMap', getName: 'name', getMass: 'number', getPhysics: 'physics',
});

const DECODE = {
	number: (value) => fromWire(value),
	numbers: (values) => values.map(fromWire),
	refs: (refs, session) => refs.map((ref) => session.object(ref.ref)),
	ids: (refs, session) => refs.map((ref) => session.resolve(ref.ref)),
	contacts: (forces, session) => forces.map((force) => ({ ...force, other: session.resolve(force.other) })),
};

// Give every class that has a read its exact form.
export function addExactReads(...classes) {
	for (const Class of classes) {
		for (const [name, returns] of Object.entries(READS)) {
			if (typeof Class.prototype[name] !== 'function' || Object.hasOwn(Class.prototype, `${name}Exact`)) continue;
			Object.defineProperty(Class.prototype, `${name}Exact`, {
				async value(...args) {
					const session = this.vp.session;
					const result = await session.call(this.vp.id, name, args, { wait: true });
					return (DECODE[returns] ?? ((x) => x))(result, session);
				},
				writable: true,
				configurable: true,
			});
		}
	}
}
