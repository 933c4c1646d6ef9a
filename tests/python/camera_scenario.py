"""A yaw snake with a head camera and a red ball, made for the tests from
mrsim's own chain generator (Scenario.chain) plus a <Camera> and a
<SceneObject> in its XML."""

import mrsim

CAMERA = """<cameras xmlns="Assembly"><Camera>
  <sensorPosition>4</sensorPosition><fovy>{fovy}</fovy>
  <width>{width}</width><height>{height}</height><rate>10</rate>
  <near>0.01</near><far>10</far><tilt>{tilt}</tilt><noise>0</noise>
  <seed>1</seed></Camera></cameras>
      </SensorModule>"""

BALL = """<sceneObjects xmlns="Assembly"><SceneObject>
    <guid>ball</guid>
    <size><x>{d}</x><y>{d}</y><z>{d}</z></size>
    <position><x>{x}</x><y>{y}</y><z>{z}</z></position>
    <rotation><x>0</x><y>0</y><z>0</z></rotation>
    <quatRotation><x>0</x><y>0</y><z>0</z><w>1</w></quatRotation>
    <materialName>red</materialName><shape>Sphere</shape>
    <mass>1</mass><isStatic>true</isStatic>
  </SceneObject>{post}</sceneObjects>"""

# A static post with a fixed camera on its back face (looking along -x).
POST = """<SceneObject>
    <guid>post</guid>
    <size><x>0.04</x><y>0.04</y><z>0.04</z></size>
    <position><x>{x}</x><y>{y}</y><z>{z}</z></position>
    <materialName>plastic</materialName><shape>Box</shape>
    <mass>1</mass><isStatic>true</isStatic>
    <cameras><Camera><sensorPosition>5</sensorPosition>
      <width>80</width><height>60</height><tilt>{tilt}</tilt>
    </Camera></cameras>
  </SceneObject>"""


def camera_snake(ball=(0.8, 0.0), width=80, height=60, fovy=60, tilt=5,
                 modules=8, diameter=0.15, camera=True, post=None,
                 post_tilt=0):
    """The scenario: `modules` yaw modules, a camera on the front face of
    a sensor module ahead of module 0 (its head, at x = 0.075), a static
    red ball of `diameter` m on the ground at `ball` (x, y), and with
    `post` (x, y, z) a static post whose camera looks back along -x,
    `post_tilt` degrees down."""
    xml = mrsim.Scenario.chain(modules=modules, pattern="yaw", sensors=[-1],
                               friction=0.8).to_xml()
    if camera:
        xml = xml.replace("</SensorModule>", CAMERA.format(
            fovy=fovy, width=width, height=height, tilt=tilt), 1)
    xml = xml.replace('<sceneObjects xmlns="Assembly" />', BALL.format(
        d=diameter, x=ball[0], y=ball[1], z=diameter / 2,
        post="" if post is None else POST.format(
            x=post[0], y=post[1], z=post[2], tilt=post_tilt)))
    return mrsim.Scenario.from_xml(xml, "camera_snake")
