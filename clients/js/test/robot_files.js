// A small robot as a URDF, made by the tests: a palm box and one finger of two links (the
// second follows the first through <mimic>), every shape a primitive (no mesh files).

export const FINGER_LIMITS = [0, 1.5];
export const MIMIC = [0.5, 0.1];

export function fingerUrdf() {
	return `<robot name="one_finger">
  <link name="palm"><visual><geometry><box size="0.08 0.1 0.02"/></geometry>
    <material name="blue"><color rgba="0.2 0.3 0.9 1"/></material></visual>
    <collision><geometry><box size="0.08 0.1 0.02"/></geometry></collision></link>
  <link name="proximal"><visual><origin xyz="0 0 0.02"/><geometry><cylinder radius="0.008" length="0.04"/></geometry></visual>
    <collision><origin xyz="0 0 0.02"/><geometry><cylinder radius="0.008" length="0.04"/></geometry></collision></link>
  <link name="distal"><visual><origin xyz="0 0 0.015"/><geometry><sphere radius="0.01"/></geometry></visual></link>
  <joint name="knuckle" type="revolute"><parent link="palm"/><child link="proximal"/>
    <origin xyz="0 0.05 0" rpy="-1.5707963 0 0"/><axis xyz="1 0 0"/>
    <limit lower="${FINGER_LIMITS[0]}" upper="${FINGER_LIMITS[1]}" effort="0.3" velocity="2"/></joint>
  <joint name="tip" type="revolute"><parent link="proximal"/><child link="distal"/>
    <origin xyz="0 0 0.04"/><axis xyz="1 0 0"/>
    <limit lower="${FINGER_LIMITS[0]}" upper="${FINGER_LIMITS[1]}" effort="0.3" velocity="2"/>
    <mimic joint="knuckle" multiplier="${MIMIC[0]}" offset="${MIMIC[1]}"/></joint>
</robot>`;
}

// The robot file the server at `http` keeps for fingerUrdf().
export async function uploadedRobot(http) {
	const answer = await fetch(new URL('/api/robots', http), { method: 'POST', body: fingerUrdf() });
	if (!answer.ok) throw new Error(`upload: ${answer.status} ${await answer.text()}`);
	return (await answer.json()).file;
}
