using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Alignment;

/// <summary>A sample lying turned on the stage: find its two marks, align, plan, and the plan burns the marks where they were found.</summary>
public class AlignmentEndToEndTests
{
    [Theory]
    [InlineData(17.0)]
    [InlineData(-40.0)]
    [InlineData(180.0)]
    public void AlignAndPlan_RotatedSample_BurnsTheMarksWhereTheyWereFound(double degrees)
    {
        // A 4 x 3 mm job at 20 µm per pixel: two 5 x 5 px marks centred at (0.51, 0.51) and (3.49, 2.49) mm.
        const double PitchUm = 20;
        var job = new BitMask(200, 150);
        Block(job, 23, 23);
        Block(job, 172, 122);
        (double X, double Y) n1 = (0.51, 0.51), n2 = (3.49, 2.49);

        // The sample sits turned by the angle with the job's corner at stage (25, 20) mm: where the marks are found.
        var a = degrees * Math.PI / 180;
        (double X, double Y) Found((double X, double Y) n) => (25 + (Math.Cos(a) * n.X) - (Math.Sin(a) * n.Y), 20 + (Math.Sin(a) * n.X) + (Math.Cos(a) * n.Y));
        var (m1, m2) = (Found(n1), Found(n2));

        var alignment = FiducialAlignment.Solve(new Fiducial(n1.X, n1.Y, m1.X, m1.Y), new Fiducial(n2.X, n2.Y, m2.X, m2.Y));
        var aligned = MaskResampler.Resample(job, PitchUm, alignment.Transform);
        var report = GeometryResolver.Resolve(SizeSpec.Pitch(PitchUm), aligned.Mask.Width, aligned.Mask.Height, new OriginMm(aligned.OriginXMm, aligned.OriginYMm), MachineProfile.Default);
        var plan = new RasterPlan(aligned.Mask, report.Geometry);

        // Every burn is along X, and the burnt length near each found mark has its centre within a pixel of it.
        var burns = plan.Moves().Where(m => m.Kind == MoveKind.Burn).ToList();
        Assert.All(burns, b => Assert.Equal(b.Y0, b.Y1));
        foreach (var mark in new[] { m1, m2 })
        {
            double length = 0, sumX = 0, sumY = 0;
            foreach (var b in burns)
            {
                var (x0, x1, y) = (b.X0 * report.Geometry.MicrostepUm / 1000, b.X1 * report.Geometry.MicrostepUm / 1000, b.Y0 * report.Geometry.MicrostepUm / 1000);
                if (Math.Abs(y - mark.Y) < 0.2 && Math.Abs(((x0 + x1) / 2) - mark.X) < 0.2)
                {
                    var l = Math.Abs(x1 - x0);
                    length += l;
                    sumX += l * (x0 + x1) / 2;
                    sumY += l * y;
                }
            }

            Assert.True(length > 0, $"nothing burnt near ({mark.X}, {mark.Y})");
            Assert.InRange(sumX / length, mark.X - 0.02, mark.X + 0.02);
            Assert.InRange(sumY / length, mark.Y - 0.02, mark.Y + 0.02);
        }
    }

    private static void Block(BitMask mask, int left, int top)
    {
        for (var y = top; y < top + 5; y++)
        {
            for (var x = left; x < left + 5; x++)
            {
                mask[x, y] = true;
            }
        }
    }
}
