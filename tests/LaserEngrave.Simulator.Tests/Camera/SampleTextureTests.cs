using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.Simulator.Tests.Camera;

/// <summary>The twin sample's fast frame fill agrees with its point-by-point definition (the camera's images depend on it).</summary>
public class SampleTextureTests
{
    [Theory]
    [InlineData(20_000.3, 25_000.7, 1.37, 0.055, -0.055, 1.37)]
    [InlineData(-13.2, 4.9, -0.85, 0.03, 0.03, 0.85)]
    [InlineData(31_000, 17_000, 2.1, -1.28, -1.28, -2.1)]
    public void Fill_AnyAffineFootprint_SameAsAtPointByPoint(double x0, double y0, double xPerU, double yPerU, double xPerV, double yPerV)
    {
        var texture = new SampleTexture(37);
        const int w = 67, h = 41;
        var image = new double[w * h];

        texture.Fill(image, w, h, x0, y0, xPerU, yPerU, xPerV, yPerV);

        var worst = 0.0;
        for (var v = 0; v < h; v++)
        {
            for (var u = 0; u < w; u++)
            {
                var expected = texture.At(x0 + (xPerU * u) + (xPerV * v), y0 + (yPerU * u) + (yPerV * v));
                worst = Math.Max(worst, Math.Abs(image[(v * w) + u] - expected));
            }
        }

        Assert.True(worst < 1e-9, $"the fill differs from the texture by up to {worst}");
    }
}
