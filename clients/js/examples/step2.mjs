// The manual's Step 2 in Node: only the import and connect() are new.
import * as Prosthetic from "../virtual-prosthetics.js";
await Prosthetic.connect({ url: process.env.VP_URL, scene: process.env.VP_SCENE });
var robot = new Prosthetic.Robot;
robot.attachChain(
new Prosthetic.MotorZ,
new Prosthetic.EdgedFinger,
new Prosthetic.MotorZ,
new Prosthetic.EdgedFinger,
new Prosthetic.MotorZ,
new Prosthetic.EdgedFinger,
);
