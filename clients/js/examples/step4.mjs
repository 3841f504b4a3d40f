// The manual's Step 4 in Node: only the import and connect() are new.
import * as Prosthetic from "../virtual-prosthetics.js";
await Prosthetic.connect({ url: process.env.VP_URL, scene: process.env.VP_SCENE });
var robot = new Prosthetic.Robot;
robot.attachChain(
new Prosthetic.MotorZ( -0.7, 0.7, 0, 0.2, 0.6 ),
new Prosthetic.EdgedFinger( 1, 1, 0.1 ),
new Prosthetic.MotorZ( -1.6, 0, 0, 0.4, 0.3 ),
new Prosthetic.EdgedFinger( 2 ),
new Prosthetic.MotorZ( -1.6, 0, 0, 0.4, 0.2 ),
new Prosthetic.EdgedFinger( 0.7, 0.1 ),
);
Prosthetic.setAnimation( loop );
function loop( t )
{
robot.setAngles(
-0.7*Math.sin(2*t+3),
-1.6*(0.5 + 0.5*Math.sin(2*t+1)),
-1.6*(0.5 + 0.5*Math.sin(2*t))
);
}
