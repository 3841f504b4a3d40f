// The manual's Step 3 in Node: only the import and connect() are new.
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
Prosthetic.setAnimation( loop );
function loop( t )
{
robot.setAngles(
-0.7*Math.sin(t),
-1.6*(0.5 + 0.5*Math.sin(t)),
-1.6*(0.5 + 0.5*Math.sin(t))
);
}
