using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class MoveCsvWriterTests
{
    [Fact]
    public void Write_OverscanPlan_WritesHeaderAndOverscanAsTravel()
    {
        var mask = TestMasks.FromRows(".#.");
        var options = new PlanOptions { OverscanMm = 100 * TestMasks.Microstep / 1000 };
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, ox: 1000), options);
        using var writer = new StringWriter();
        MoveCsvWriter.Write(plan, writer);

        Assert.Equal("kind,x0,y0,x1,y1\ntravel,1900,500,2000,500\nburn,2000,500,3000,500\ntravel,3000,500,3100,500\n", writer.ToString());
    }

    [Fact]
    public void Write_RandomPlan_OneLinePerMoveMatchingFormatLine()
    {
        var mask = TestMasks.Random(new Random(5), 80, 12);
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, pitch: 123.456, ox: 777.7));
        using var writer = new StringWriter();
        MoveCsvWriter.Write(plan, writer);

        var lines = writer.ToString().Split('\n', StringSplitOptions.RemoveEmptyEntries);
        Assert.Equal(MoveCsvWriter.Header, lines[0]);
        Assert.Equal(plan.Moves().Select(m => MoveCsvWriter.FormatLine(m)), lines.Skip(1));
    }
}
