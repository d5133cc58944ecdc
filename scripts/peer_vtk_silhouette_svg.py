#!/usr/bin/python3
# The peer's picture for the README: VTK's mesh-based silhouette of the Cranium CT (Flying Edges iso-surface, then
# vtkPolyDataSilhouette for one camera), projected with the same perspective camera as a `camera.set` line and written
# as an SVG line drawing, to set beside `volume.export` of the same view. Needs Debian's python3-vtk9 and
# python3-numpy (scripts/packages.txt).
#   scripts/peer_vtk_silhouette_svg.py MATRIX.dat ISO OUT.svg EYE_X EYE_Y EYE_Z TARGET_X TARGET_Y TARGET_Z [FOV W H]
# MATRIX.dat: the int16 matrix inside Cranium.inv3 (tar -xzf assets/data/Cranium.inv3). Up is +z (the scan's).
import sys
import numpy as np
import vtk
from vtk.util import numpy_support as ns

path, iso, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
eye = np.array([float(v) for v in sys.argv[4:7]])
target = np.array([float(v) for v in sys.argv[7:10]])
fov = float(sys.argv[10]) if len(sys.argv) > 10 else 30.0
w = int(sys.argv[11]) if len(sys.argv) > 11 else 960
h = int(sys.argv[12]) if len(sys.argv) > 12 else 720
vol = np.fromfile(path, dtype='<i2').reshape(108, 256, 256)
img = vtk.vtkImageData(); img.SetDimensions(256, 256, 108); img.SetSpacing(0.9570312, 0.9570312, 1.5)
img.GetPointData().SetScalars(ns.numpy_to_vtk(vol.ravel(), deep=True, array_type=vtk.VTK_SHORT))
fe = vtk.vtkFlyingEdges3D(); fe.SetInputData(img); fe.SetValue(0, iso); fe.ComputeNormalsOff(); fe.Update()
cam = vtk.vtkCamera(); cam.SetPosition(*eye); cam.SetFocalPoint(*target); cam.SetViewUp(0, 0, 1)
sil = vtk.vtkPolyDataSilhouette(); sil.SetInputData(fe.GetOutput()); sil.SetCamera(cam)
sil.SetDirectionToCameraOrigin(); sil.BorderEdgesOff(); sil.Update()
lines = sil.GetOutput()
pts = ns.vtk_to_numpy(lines.GetPoints().GetData()).astype(float)
# The perspective of core::Camera: look-at with up +z, vertical field of view fov, pixels with y down.
f = (target - eye) / np.linalg.norm(target - eye)
r = np.cross(f, [0, 0, 1]); r /= np.linalg.norm(r)
u = np.cross(r, f)
d = pts - eye
x, y, z = d @ r, d @ u, d @ f
s = (h / 2) / np.tan(np.radians(fov) / 2)
px, py = w / 2 + s * x / z, h / 2 - s * y / z
conn = ns.vtk_to_numpy(lines.GetLines().GetData())
segs = []
i = 0
while i < len(conn):
    n = conn[i]; ids = conn[i + 1:i + 1 + n]; i += n + 1
    segs.append(" ".join(f"M{px[ids[0]]:.1f},{py[ids[0]]:.1f}" if k == 0 else f"L{px[j]:.1f},{py[j]:.1f}"
                         for k, j in enumerate(ids)))
with open(out, "w") as o:
    o.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">\n'
            f'<rect width="{w}" height="{h}" fill="white"/>\n'
            f'<path fill="none" stroke="black" stroke-width="1.5" d="{" ".join(segs)}"/>\n</svg>\n')
print(f"vtk silhouette: {fe.GetOutput().GetNumberOfPolys()} triangles, {len(segs)} segments -> {out}")
