"""The numpy functions of ``pointsetsurfaces`` (project, classify, sample, mesh, read) against
analytic truths, in whichever interpreter runs this file (Debian's python3 or pvpython):

    PYTHONPATH=build/lib/python3.11/site-packages python3 tests/python/test_numpy_api.py [TestClass ...]

Exit status 0 when every test passes, 1 otherwise (unittest's).
"""
import contextlib
import inspect
import os
import sys
import tempfile
import unittest
import warnings

import numpy as np

import pointsetsurfaces as pss
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkSMPTools


def sphere(n, noise=0.0, seed=1):
    """n points on the unit sphere (uniform directions), moved radially by Gaussian noise."""
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n, 3))
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    return p * (1.0 + noise * rng.normal(size=(n, 1)))


def point_polydata(points):
    """A vtkPolyData of the (N, 3) points, without cells."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    poly = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points, deep=True))
    poly.SetPoints(vtk_points)
    return poly


def write_vtp(test, poly, path):
    """Writes poly to path with VTK's XML writer, asserting that it succeeded."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(poly)
    test.assertEqual(writer.Write(), 1)


def circle(n):
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.column_stack([np.cos(t), np.sin(t)])


@contextlib.contextmanager
def stderr_captured():
    """Everything written to file descriptor 2 (where VTK prints its errors) inside the block."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as sink:
        os.dup2(sink.fileno(), 2)
        text = []
        try:
            yield text
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            sink.seek(0)
            text.append(sink.read().decode(errors="replace"))


class MeshTest(unittest.TestCase):
    def test_sphere_from_numpy_is_one_closed_surface_on_the_sphere(self):
        # Noise of 0.2% of the radius; the centre-of-mass surface of a sphere sampled this densely
        # lies within about h^2 / R (h ~ 0.11 here) inside it.
        points = sphere(3000, noise=0.002)
        m = pss.mesh(points)
        v, t = m.vertices, m.triangles
        self.assertEqual(v.shape[1], 3)
        self.assertEqual(t.shape[1], 3)
        self.assertGreater(len(t), 1000)
        radius = np.linalg.norm(v, axis=1)
        self.assertLess(np.abs(radius - 1.0).max(), 0.03, "a vertex is off the unit sphere")
        # Closed: every edge in exactly two triangles; a sphere: V - E + F = 2 (counted here, not
        # read from the filter's field data, which must agree).
        edges = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
        unique, counts = np.unique(edges, axis=0, return_counts=True)
        self.assertTrue(np.all(counts == 2), "an edge is not shared by exactly two triangles")
        self.assertEqual(len(v) - len(unique) + len(t), 2)
        self.assertEqual(m.info["EulerCharacteristic"], 2)
        self.assertEqual(m.info["Components"], 1)
        self.assertEqual(m.info["BoundaryEdges"], 0)
        self.assertEqual(len(m.Normals), len(v))
        self.assertTrue(np.all(m.DomainLabel == 0))
        # Normals point outwards on a sphere (consistent orientation, triangles counter-clockwise).
        self.assertGreater(np.min(np.sum(m.Normals * v, axis=1)), 0.9)

    def test_circle_from_a_two_column_array_gives_segments_in_the_plane(self):
        m = pss.mesh(circle(300))
        self.assertEqual(m.vertices.shape[1], 2)
        self.assertEqual(m.segments.shape[1], 2)
        self.assertNotIn("triangles", m)
        self.assertLess(np.abs(np.linalg.norm(m.vertices, axis=1) - 1.0).max(), 0.03)
        # A closed curve: every vertex ends two segments.
        self.assertTrue(np.all(np.bincount(m.segments.ravel(), minlength=len(m.vertices)) == 2))

    def test_as_polydata(self):
        poly = pss.mesh(sphere(2000), as_polydata=True)
        self.assertEqual(poly.GetClassName(), "vtkPolyData")
        self.assertGreater(poly.GetNumberOfPolys(), 1000)
        self.assertIsNotNone(poly.GetPointData().GetArray("Normals"))


class ProjectTest(unittest.TestCase):
    def plane(self):
        # Jittered grid on the tilted plane z = 0.3 x - 0.2 y, and its unit normal.
        rng = np.random.default_rng(3)
        xy = np.stack(np.meshgrid(np.arange(30.0), np.arange(30.0)), -1).reshape(-1, 2)
        xy += rng.uniform(-0.3, 0.3, xy.shape)
        normal = np.array([-0.3, 0.2, 1.0]) / np.linalg.norm([-0.3, 0.2, 1.0])
        return np.column_stack([xy, 0.3 * xy[:, 0] - 0.2 * xy[:, 1]]), normal, rng

    def test_points_off_a_plane_land_on_it_for_every_variant(self):
        cloud, normal, rng = self.plane()
        interior = cloud[np.all((cloud[:, :2] > 8) & (cloud[:, :2] < 21), axis=1)]
        for variant in pss.VARIANTS:
            for procedure in ("extremal", "plane"):
                with self.subTest(variant=variant, procedure=procedure):
                    h = pss.project(cloud, interior[:1], variant=variant).info["h"]
                    start = interior + rng.uniform(-0.5, 0.5, (len(interior), 1)) * h * normal
                    r = pss.project(cloud, start, variant=variant, procedure=procedure)
                    self.assertEqual(r.points.shape, start.shape)
                    self.assertTrue(np.all(r.StopReason == 0))
                    # The plane is the surface of a planar cloud for every definition (the cloud
                    # is symmetric about it); integral and delta read delta from a lattice,
                    # accurate to about 6e-4 h.
                    tolerance = 2e-3 if variant in ("integral", "delta") else 1e-6
                    distance = np.abs((r.points - cloud[0]) @ normal)
                    self.assertLess(distance.max(), tolerance * h)
                    self.assertTrue(np.allclose(np.abs(r.Normal @ normal), 1.0, atol=1e-3))
                    self.assertTrue(np.allclose(r.Displacement, r.points - start))

    def test_apss_with_given_normals_lands_on_the_sphere(self):
        cloud = sphere(3000)
        r = pss.project(cloud, variant="apss", normals=cloud, procedure="plane")
        self.assertTrue(np.all(r.StopReason == 0))
        self.assertLess(np.abs(np.linalg.norm(r.points, axis=1) - 1.0).max(), 1e-9)
        self.assertEqual(r.info.get("h") > 0.0, True)
        with self.assertRaises(pss.InputError):
            pss.project(cloud, variant="apss", normals=cloud[:10])
        bad = cloud.copy()
        bad[5] = 0.0
        with self.assertRaises(pss.Error) as raised:
            pss.project(cloud, variant="rimls", normals=bad)
        self.assertIn("normal of point 5", str(raised.exception))

    def test_explicit_h_is_used(self):
        cloud, _, _ = self.plane()
        r = pss.project(cloud, h=2.5, dimension=3)
        self.assertEqual(r.info["h"], 2.5)
        self.assertEqual(r.info["dimension"], 3)

    def test_a_scale_per_point(self):
        cloud, normal, rng = self.plane()
        start = cloud[::7] + rng.uniform(-0.3, 0.3, (len(cloud[::7]), 1)) * normal
        single = pss.project(cloud, start, h=2.5, dimension=3)
        self.assertFalse(single.info["point_scales"])
        # Equal scales given per point are the single h.
        equal = pss.project(cloud, start, point_scales=np.full(len(cloud), 2.5), dimension=3)
        self.assertTrue(equal.info["point_scales"])
        self.assertEqual(equal.info["h"], 2.5)
        self.assertLess(np.abs(equal.points - single.points).max(), 1e-12 * 2.5)
        # Scales growing tenfold across the plane still project onto it.
        varying = 1.0 + 9.0 * (cloud[:, 0] - cloud[:, 0].min()) / np.ptp(cloud[:, 0])
        r = pss.project(cloud, start, point_scales=varying, dimension=3)
        self.assertTrue(np.all(r.StopReason == 0))
        self.assertLess(np.abs((r.points - cloud[0]) @ normal).max(), 1e-6)
        # A point array of the cloud, by name.
        poly = pss.project(cloud, as_polydata=True, h=2.5)
        scale = numpy_support.numpy_to_vtk(np.full(poly.GetNumberOfPoints(), 2.5), deep=True)
        scale.SetName("Radius")
        poly.GetPointData().AddArray(scale)
        named = pss.project(poly, poly, point_scales="Radius")
        self.assertTrue(named.info["point_scales"])
        self.assertEqual(named.info["h"], 2.5)

    def test_a_sensor_frame_read_from_a_file_keeps_its_viewpoint(self):
        # An even sphere takes one h; with the field data Viewpoint that a PCD frame carries it is
        # a sensor frame and takes a scale per point, also when given by its path.
        from vtkmodules.vtkCommonCore import vtkDoubleArray

        points = sphere(800)
        poly = point_polydata(points)
        self.assertFalse(pss.project(points).info["point_scales"])
        viewpoint = vtkDoubleArray()
        viewpoint.SetName("Viewpoint")
        for value in (0.0, 0.0, 5.0):
            viewpoint.InsertNextValue(value)
        poly.GetFieldData().AddArray(viewpoint)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "frame.vtp")
            write_vtp(self, poly, path)
            self.assertTrue(pss.project(path).info["point_scales"])

    def test_circle_in_two_columns(self):
        c = circle(200)
        r = pss.project(c, 1.1 * c)
        self.assertEqual(r.points.shape, (200, 2))
        self.assertEqual(r.info["dimension"], 2)
        self.assertLess(np.abs(np.linalg.norm(r.points, axis=1) - 1.0).max(), 0.02)

    def test_cloud_from_a_file_equals_the_array(self):
        points = sphere(1500)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cloud.xyz")
            np.savetxt(path, points, fmt="%.17g")
            from_file = pss.project(path)
        from_array = pss.project(points)
        for name in from_array:
            self.assertTrue(np.array_equal(from_file[name], from_array[name]), name)


class ClassifyTest(unittest.TestCase):
    def test_labels_one_per_start_point(self):
        cloud = sphere(2000)
        starts = np.concatenate([cloud[:300], 3.0 * cloud[:50]])
        r = pss.classify(cloud, starts)
        self.assertEqual(r.DomainLabel.shape, (350,))
        self.assertTrue(set(np.unique(r.DomainLabel)) <= {0, 1, 2, 3})
        # Points on the sphere are fixed points of their own projection: in the domain.
        self.assertTrue(np.all(r.DomainLabel[:300] == 0))
        for name in ("DistanceToCloud", "NormalAngle", "StartAngle", "StartStability", "StopReason", "points"):
            self.assertEqual(len(r[name]), 350, name)

    def test_a_tight_normal_angle_changes_nothing_on_the_sphere_and_two_columns_work(self):
        r = pss.classify(circle(200), max_normal_angle=5.0, max_distance=0.5)
        self.assertEqual(r.DomainLabel.shape, (200,))
        self.assertTrue(np.all(r.DomainLabel == 0))


class SampleTest(unittest.TestCase):
    def test_grid_shape_order_and_delta_bound(self):
        cloud = sphere(1500)
        s = pss.sample(cloud, grid=(21, 11, 5))
        self.assertEqual(s.points.shape, (21, 11, 5, 3))
        self.assertEqual(s.Normal.shape, (21, 11, 5, 3))
        for name in ("Energy", "Delta", "ImplicitG", "Stability", "ExtremumType", "Valid"):
            self.assertEqual(s[name].shape, (21, 11, 5), name)
        self.assertEqual(tuple(s.info["dimensions"]), (21, 11, 5))
        # [i, j, k] is (x, y, z): x grows with i only, y with j only, z with k only.
        self.assertTrue(np.all(np.diff(s.points[:, 0, 0, 0]) > 0))
        self.assertTrue(np.all(np.diff(s.points[0, :, 0, 1]) > 0))
        self.assertTrue(np.all(np.diff(s.points[0, 0, :, 2]) > 0))
        self.assertTrue(np.all(s.points[:, 3, 2, 1] == s.points[0, 3, 2, 1]))
        self.assertTrue(np.all(s.Valid == 1))
        # delta(x) is at least the squared distance to the nearest cloud point, everywhere.
        grid = s.points.reshape(-1, 3)
        nearest = np.min(np.sum((grid[:, None, :] - cloud[None, :, :]) ** 2, axis=2), axis=1)
        self.assertTrue(np.all(s.Delta.reshape(-1) >= nearest * (1.0 - 1e-9)))

    def test_probe_points_and_the_sign_of_g(self):
        cloud = sphere(2000)
        probe = np.array([[0.7, 0.0, 0.0], [0.0, -0.6, 0.0], [1.3, 0.0, 0.0], [0.0, 0.0, 1.4]])
        s = pss.sample(cloud, probe)
        self.assertEqual(s.ImplicitG.shape, (4,))
        self.assertEqual(s.Normal.shape, (4, 3))
        # Normals oriented away from the centroid: g < 0 inside the sphere, > 0 outside.
        self.assertTrue(np.all(s.ImplicitG[:2] < 0) and np.all(s.ImplicitG[2:] > 0), s.ImplicitG)

    def test_two_dimensional_grid(self):
        s = pss.sample(circle(200), grid=(31, 21))
        self.assertEqual(s.points.shape, (31, 21, 1, 2))
        self.assertEqual(s.Normal.shape, (31, 21, 1, 2))


class ReadTest(unittest.TestCase):
    def test_vtp_written_by_vtk_round_trips(self):
        from vtkmodules.util.numpy_support import numpy_to_vtk

        points = sphere(500, noise=0.01)
        weight = np.linspace(0.0, 1.0, 500)
        label = np.arange(500, dtype=np.int32) % 7
        poly = point_polydata(points)
        for name, values in (("Weight", weight), ("Label", label)):
            array = numpy_to_vtk(values, deep=True)
            array.SetName(name)
            poly.GetPointData().AddArray(array)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cloud.vtp")
            write_vtp(self, poly, path)
            r = pss.read(path)
            self.assertTrue(np.array_equal(r.points, points))
            self.assertTrue(np.array_equal(r.Weight, weight))
            self.assertTrue(np.array_equal(r.Label, label))
            self.assertEqual(pss.read(path, as_polydata=True).GetNumberOfPoints(), 500)

    def test_csv_with_header_and_xyz(self):
        points = sphere(100)
        with tempfile.TemporaryDirectory() as tmp:
            csv = os.path.join(tmp, "cloud.csv")
            with open(csv, "w") as f:
                f.write("# a comment\nintensity,X,y,z\n")
                for i, (x, y, z) in enumerate(points):
                    f.write("%d,%.17g,%.17g,%.17g\n" % (i, x, y, z))
            r = pss.read(csv)
            self.assertTrue(np.array_equal(r.points, points))
            self.assertTrue(np.array_equal(r.intensity, np.arange(100.0)))
            xyz = os.path.join(tmp, "cloud.xyz")
            np.savetxt(xyz, points[:, :2], fmt="%.17g")
            r = pss.read(xyz)
            self.assertTrue(np.array_equal(r.points[:, :2], points[:, :2]))
            self.assertTrue(np.all(r.points[:, 2] == 0.0))

    def test_pcd_when_the_module_has_its_reader(self):
        if not (hasattr(pss, "vtkPCDReader") and hasattr(pss, "vtkPCDWriter")):
            self.skipTest("this build has no vtkPCDReader/vtkPCDWriter")
        points = sphere(200)
        poly = point_polydata(points)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cloud.pcd")
            writer = pss.vtkPCDWriter()
            writer.SetFileName(path)
            writer.SetInputData(poly)
            writer.Write()
            r = pss.read(path)
        # PCD stores float32 or float64 depending on the writer's setting: compare at float32.
        self.assertTrue(np.allclose(r.points, points, rtol=0, atol=1e-6))

    def test_errors(self):
        with self.assertRaises(FileNotFoundError):
            pss.read("/nonexistent/cloud.vtp")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cloud.abc")
            open(path, "w").close()
            with self.assertRaisesRegex(pss.InputError, "unknown file format"):
                pss.read(path)
            path = os.path.join(tmp, "broken.vtp")
            with open(path, "w") as f:
                f.write("<VTKFile type='PolyData'><broken")
            # The reader's own error is raised; its XML parser, an object inside it that takes no
            # observer, still logs its line on stderr.
            with self.assertRaisesRegex(pss.Error, "vtkXMLPolyDataReader: Error parsing input file"):
                pss.read(path)


class ProgressTest(unittest.TestCase):
    def test_fractions_increase_to_one(self):
        for function in (pss.project, pss.mesh):
            with self.subTest(function=function.__name__):
                seen = []
                function(sphere(20000), progress=seen.append)
                # Several reports during the run, not only the final one.
                self.assertGreater(len(seen), 5)
                self.assertTrue(all(0.0 <= f <= 1.0 for f in seen))
                self.assertTrue(all(a < b for a, b in zip(seen, seen[1:])), seen)
                self.assertEqual(seen[-1], 1.0)

    def test_an_exception_in_the_callback_stops_the_run_and_is_raised(self):
        class Stop(Exception):
            pass

        calls = []

        def stop(fraction):
            calls.append(fraction)
            if fraction > 0.2:
                raise Stop()

        with self.assertRaises(Stop):
            pss.project(sphere(20000), progress=stop)
        self.assertLess(calls[-1], 1.0)


class ThreadsTest(unittest.TestCase):
    def test_one_and_two_threads_give_identical_arrays(self):
        cloud = sphere(5000, noise=0.005)
        before = vtkSMPTools.GetEstimatedNumberOfThreads()
        for function in (pss.project, pss.classify, pss.mesh):
            with self.subTest(function=function.__name__):
                # The count in force during each run, read while it runs.
                counts = {1: set(), 2: set()}
                one = function(cloud, threads=1,
                               progress=lambda f: counts[1].add(vtkSMPTools.GetEstimatedNumberOfThreads()))
                two = function(cloud, threads=2,
                               progress=lambda f: counts[2].add(vtkSMPTools.GetEstimatedNumberOfThreads()))
                self.assertEqual(counts, {1: {1}, 2: {2}})
                self.assertEqual(sorted(one), sorted(two))
                for name in one:
                    self.assertTrue(np.array_equal(one[name], two[name], equal_nan=True), name)
        s1 = pss.sample(cloud, grid=(15, 15, 15), threads=1)
        s2 = pss.sample(cloud, grid=(15, 15, 15), threads=2)
        for name in s1:
            self.assertTrue(np.array_equal(s1[name], s2[name]), name)
        # The count is one call's: the process's setting is back afterwards.
        self.assertEqual(vtkSMPTools.GetEstimatedNumberOfThreads(), before)


class ErrorsTest(unittest.TestCase):
    def assert_raises_quietly(self, exception, text, function, *args, **kwargs):
        """function raises exception with text in its message, and prints nothing."""
        with stderr_captured() as printed, self.assertRaises(exception) as raised:
            function(*args, **kwargs)
        self.assertIn(text, str(raised.exception))
        self.assertEqual(printed[0], "", "printed on stderr")
        return raised.exception

    def test_h_not_positive_carries_the_filters_message(self):
        for function in (pss.project, pss.classify, pss.sample, pss.mesh):
            for h in (0.0, -1.0, float("nan")):
                with self.subTest(function=function.__name__, h=h):
                    e = self.assert_raises_quietly(pss.Error, "the scale h must be a positive finite number",
                                                   function, sphere(200), h=h)
                    self.assertNotIsInstance(e, pss.InputError)

    def test_empty_array(self):
        for function in (pss.project, pss.classify, pss.sample, pss.mesh):
            with self.subTest(function=function.__name__):
                self.assert_raises_quietly(pss.Error, "the point cloud is empty", function, np.zeros((0, 3)))

    def test_nan_point(self):
        cloud = sphere(300)
        cloud[17, 1] = np.nan
        for function in (pss.project, pss.classify, pss.sample, pss.mesh):
            with self.subTest(function=function.__name__):
                self.assert_raises_quietly(pss.InputError, "index 17", function, cloud)
        # Allowed, the filter leaves the point out and says so: a warning with its message.
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            r = pss.project(cloud, cloud[:20], nonfinite="allow")
        messages = [str(w.message) for w in caught if issubclass(w.category, pss.SurfaceWarning)]
        self.assertTrue(any("1 cloud point(s) with NaN or infinite coordinates were left out" in m for m in messages),
                        messages)
        self.assertEqual(r.StopReason[17], 4)
        self.assertTrue(np.all(np.delete(r.StopReason, 17) == 0))
        self.assert_raises_quietly(pss.Error, "no point with finite coordinates", pss.project,
                                   np.full((10, 3), np.nan), nonfinite="allow")

    def test_wrong_shape_or_type(self):
        for bad in (np.zeros((10, 4)), np.zeros(3), np.zeros((2, 3, 3)), [[0.0, 1.0, "a"]], None):
            with self.subTest(bad=bad):
                self.assert_raises_quietly(pss.InputError, "cloud", pss.project, bad)
        self.assert_raises_quietly(pss.InputError, "start", pss.project, sphere(100), np.zeros((5, 5)))

    def test_parameters_refused(self):
        cloud = sphere(200)
        self.assert_raises_quietly(pss.InputError,
                                   "variant must be one of levin, normalized, com, integral, delta, apss, rimls",
                                   pss.project, cloud, variant="mls2")
        self.assert_raises_quietly(pss.InputError, "tolerance must be within", pss.project, cloud, tolerance=5.0)
        self.assert_raises_quietly(pss.InputError, "cell must be within", pss.mesh, cloud, cell=0.01)
        # A clamp would let NaN through to the filter.
        self.assert_raises_quietly(pss.InputError, "tolerance must be a number", pss.project, cloud,
                                   tolerance=float("nan"))
        self.assert_raises_quietly(pss.InputError, "band must be", pss.mesh, cloud, band=float("inf"))
        self.assert_raises_quietly(pss.InputError, "threads", pss.project, cloud, threads=-1)
        self.assert_raises_quietly(pss.InputError, "progress", pss.project, cloud, progress=3)
        self.assert_raises_quietly(pss.Error, "Dimension must be Auto (0), 2 or 3, not 1", pss.project, cloud,
                                   dimension=1)
        self.assert_raises_quietly(pss.Error, "delta lattice spacing must be 0", pss.project, cloud, variant="delta",
                                   delta_lattice=0.01)
        self.assert_raises_quietly(pss.Error, "the mesh band would have more than", pss.mesh, cloud,
                                   max_band_cells=10)
        self.assert_raises_quietly(pss.InputError, "scale_multiplier must be within", pss.project, cloud,
                                   scale_multiplier=0.0)
        self.assert_raises_quietly(pss.InputError, "point_scales must hold one value per cloud point (200)",
                                   pss.project, cloud, point_scales=np.ones(199))
        self.assert_raises_quietly(pss.InputError, "point_scales must be one of automatic, off, estimated",
                                   pss.project, cloud, point_scales="Radius")
        for bad in (0.0, -1.0, float("nan")):
            scales = np.ones(200)
            scales[5] = bad
            self.assert_raises_quietly(pss.Error, "the scale of point 5 must be a positive finite number",
                                       pss.project, cloud, point_scales=scales)
        with self.assertRaises(TypeError):
            pss.project(cloud, scale=2.0)  # not a keyword of project

    def test_variant_spellings(self):
        cloud = circle(100)
        reference = pss.project(cloud, variant="com")
        for spelling in ("CenterOfMass", "center of mass", "COM", 2):
            self.assertTrue(np.array_equal(pss.project(cloud, variant=spelling).points, reference.points), spelling)
        self.assertTrue(np.array_equal(pss.project(cloud, variant="mls").points,
                                       pss.project(cloud, variant="levin-mls").points))


class DefaultsTest(unittest.TestCase):
    """The keywords' defaults are the VTK classes' defaults (a change on one side fails here)."""

    def defaults(self, function):
        return {k: p.default for k, p in inspect.signature(function).parameters.items()
                if p.default is not inspect.Parameter.empty}

    def check(self, function, obj, names):
        d = self.defaults(function)
        for keyword, getter in names.items():
            with self.subTest(function=function.__name__, keyword=keyword):
                value = getattr(obj, getter)()
                expected = tuple(value) if isinstance(value, (tuple, list)) else value
                got = tuple(d[keyword]) if isinstance(d[keyword], (tuple, list)) else d[keyword]
                self.assertEqual(got, expected)

    def test_defaults(self):
        surface = pss.vtkPointSetSurface()
        surface_names = {"scale_neighbors": "GetScaleNeighbors", "scale_multiplier": "GetScaleMultiplier",
                         "point_scale_multiplier": "GetPointScaleMultiplier",
                         "scale_spread": "GetScaleSpreadThreshold",
                         "cutoff": "GetKernelCutoff", "quadrature": "GetQuadratureOrder",
                         "delta_lattice": "GetDeltaLatticeSpacing", "min_stability": "GetMinimumStability"}
        for function in (pss.project, pss.classify, pss.sample, pss.mesh):
            d = self.defaults(function)
            self.assertEqual(pss.VARIANTS[surface.GetVariant()], d["variant"])
            self.assertEqual(d["h"] is None, surface.GetAutomaticScale())
            self.assertEqual(d["dimension"], "auto")
            self.assertEqual(d["point_scales"], "automatic")
            self.assertEqual(surface.GetPointScales(), surface.POINT_SCALES_AUTOMATIC)
            self.assertEqual(surface.GetDimension(), surface.DIMENSION_AUTO)
            self.assertEqual(d["threads"], 0)
            self.check(function, surface, surface_names)
        projection = {"max_iterations": "GetMaxIterations", "tolerance": "GetTolerance",
                      "max_travel": "GetMaxTravel", "seek_maxima": "GetSeekMaxima"}
        self.check(pss.project, pss.vtkPointSetSurfaceProjection(), projection)
        classifier = dict(projection, max_distance="GetMaxDistance", max_normal_angle="GetMaxNormalAngle")
        self.check(pss.classify, pss.vtkPointSetSurfaceDomainClassifier(), classifier)
        self.check(pss.sample, pss.vtkPointSetSurfaceFieldSampler(),
                   {"margin": "GetSamplingMargin", "reference_point": "GetReferencePoint",
                    "reference_direction": "GetReferenceDirection", "domain_labels": "GetComputeDomainLabels",
                    "max_distance": "GetMaxDistance", "max_normal_angle": "GetMaxNormalAngle",
                    "max_iterations": "GetMaxIterations", "tolerance": "GetTolerance"})
        self.assertEqual(pss.vtkPointSetSurfaceFieldSampler().GetSampleDimensions(), (101, 101, 1))
        self.check(pss.mesh, pss.vtkPointSetSurfaceMesher(),
                   {"cell": "GetCellSize", "band": "GetBand", "project_vertices": "GetProjectVertices",
                    "max_distance": "GetMaxDistance", "max_normal_angle": "GetMaxNormalAngle",
                    "max_border_offset": "GetMaxBorderOffset", "trim_distance": "GetTrimDistance", "max_vertex_travel": "GetMaxVertexTravel", "max_seam_angle": "GetMaxSeamAngle",
                    "max_fold_angle": "GetMaxFoldAngle", "max_hole_edges": "GetMaxHoleEdges",
                    "min_piece_area": "GetMinPieceArea", "covered_piece_area": "GetCoveredPieceArea",
                    "max_band_cells": "GetMaximumNumberOfBandCells"})
        for function, obj in ((pss.project, pss.vtkPointSetSurfaceProjection()),
                              (pss.mesh, pss.vtkPointSetSurfaceMesher())):
            self.assertEqual(self.defaults(function)["procedure"], ("extremal", "plane", "automatic")[obj.GetProcedure()])

    def test_every_function_has_a_docstring(self):
        for function in (pss.project, pss.classify, pss.sample, pss.mesh, pss.read):
            self.assertGreater(len(inspect.getdoc(function) or ""), 200, function.__name__)


if __name__ == "__main__":
    print("pointsetsurfaces from %s, Python %s" % (os.path.dirname(pss.__file__), sys.version.split()[0]))
    unittest.main(verbosity=2)
