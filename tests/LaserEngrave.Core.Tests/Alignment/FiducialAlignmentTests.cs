using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Alignment;

public class FiducialAlignmentTests
{
    [Fact]
    public void Solve_MarksOfARotatedSample_RecoversAngleAndOffset()
    {
        // The sample lies turned by 12° with the job's origin at stage (20, 15) mm.
        var (s, c) = (Math.Sin(12 * Math.PI / 180), Math.Cos(12 * Math.PI / 180));
        Fiducial Mark(double x, double y) => new(x, y, 20 + (c * x) - (s * y), 15 + (s * x) + (c * y));

        var alignment = FiducialAlignment.Solve(Mark(1, 1), Mark(9, 4));

        Assert.Equal(12, alignment.Transform.AngleDegrees, 9);
        Assert.Equal(20, alignment.Transform.TranslationXMm, 9);
        Assert.Equal(15, alignment.Transform.TranslationYMm, 9);
        Assert.Equal(0, alignment.ScaleMismatchPpm, 3);
        var (x, y) = alignment.Transform.Apply(5, 5);
        Assert.Equal(20 + (c * 5) - (s * 5), x, 9);
        Assert.Equal(15 + (s * 5) + (c * 5), y, 9);
    }

    [Fact]
    public void Solve_DistanceOffWithinTolerance_ReportsMismatchAndSplitsIt()
    {
        // Marks 10 mm apart in the job, found 10.02 mm apart along X: 2000 ppm, each mark 10 µm from the fit.
        var alignment = FiducialAlignment.Solve(new Fiducial(0, 0, 5, 5), new Fiducial(10, 0, 15.02, 5), toleranceUm: 30);

        Assert.Equal(2000, alignment.ScaleMismatchPpm, 3);
        Assert.Equal(20, alignment.DistanceMismatchUm, 6);
        Assert.Equal(10, alignment.ResidualUm, 6);
        Assert.Equal(5.01, alignment.Transform.TranslationXMm, 9);
        Assert.Equal(0, alignment.Transform.AngleDegrees, 12);
    }

    [Fact]
    public void Solve_DistanceBeyondTolerance_Refuses()
    {
        var error = Assert.Throws<AlignmentException>(() => FiducialAlignment.Solve(new Fiducial(0, 0, 5, 5), new Fiducial(10, 0, 15.1, 5)));

        Assert.Contains("100 µm off", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Solve_MarksTooClose_Refuses()
    {
        Assert.Throws<AlignmentException>(() => FiducialAlignment.Solve(new Fiducial(0, 0, 5, 5), new Fiducial(0.5, 0, 5.5, 5)));
    }

    [Fact]
    public void Solve_CalibratedMachine_AlignsInTrueCoordinates()
    {
        // A square machine would read these stage positions as 10 mm apart along a 45° line; with 0.5° and ±500 ppm the
        // true positions are M times them, and the alignment must use those.
        var calibration = new AxisCalibration { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500 };
        var g = 0.5 * Math.PI / 180;
        (double X, double Y) True(double sx, double sy) => ((1.0005 * sx) - (0.9995 * sy * Math.Sin(g)), 0.9995 * sy * Math.Cos(g));
        var (t1, t2) = (True(10, 10), True(17, 17));
        var expectedAngle = Math.Atan2(t2.Y - t1.Y, t2.X - t1.X) * 180 / Math.PI;
        var trueDistance = Math.Sqrt(Math.Pow(t2.X - t1.X, 2) + Math.Pow(t2.Y - t1.Y, 2));

        var alignment = FiducialAlignment.Solve(new Fiducial(0, 0, 10, 10), new Fiducial(trueDistance, 0, 17, 17), calibration: calibration);

        Assert.Equal(expectedAngle, alignment.Transform.AngleDegrees, 9);
        Assert.Equal(t1.X, alignment.Transform.TranslationXMm, 9);
        Assert.Equal(t1.Y, alignment.Transform.TranslationYMm, 9);
    }
}
