using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

public class PathOrdererTests
{
    [Fact]
    public void Plan_ScatteredDrawing_CutsTravelByMoreThanHalfAgainstDrawingOrder()
    {
        var optimized = VectorPlanner.Plan(File("scattered.dxf"), new VectorOptions { Origin = new OriginMm(5, 5) }, MachineProfile.Default);
        var drawn = VectorPlanner.Plan(File("scattered.dxf"), new VectorOptions { Origin = new OriginMm(5, 5), Optimize = false }, MachineProfile.Default);

        // Travel summed here from each plan's own paths.
        var saved = 1 - (TravelMm(optimized) / TravelMm(drawn));
        Assert.True(saved >= 0.5, $"travel {TravelMm(optimized):0.0} mm against {TravelMm(drawn):0.0} mm in drawing order: {saved:P0} saved");
        Assert.Equal(TravelMm(drawn), optimized.TravelDrawingOrderMm, 6);
        Assert.Equal(TravelMm(optimized), optimized.TravelMm, 6);
        Assert.Equal(Shapes(drawn), Shapes(optimized));
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(3)]
    [InlineData(4)]
    [InlineData(5)]
    public void Order_RandomNestedContours_InnerAlwaysBeforeEnclosing(int seed)
    {
        var random = new Random(seed);
        var paths = new List<StagePath>();
        for (var part = 0; part < 12; part++)
        {
            // A part: a square with one to three holes, some holding an island with its own hole, and an open mark inside.
            double x = random.Next(0, 8) * 6000, y = random.Next(0, 8) * 6000;
            paths.Add(Square(x, y, 5000));
            for (var h = 0; h < random.Next(1, 4); h++)
            {
                double hx = x + 300 + (h * 1500), hy = y + 300 + random.Next(0, 3000);
                paths.Add(Square(hx, hy, 1200));
                if (random.Next(2) == 0)
                {
                    paths.Add(Circle(hx + 600, hy + 600, 300));
                    paths.Add(Square(hx + 500, hy + 500, 200));
                }
            }

            paths.Add(new StagePath([new((long)x + 4700, (long)y + 4000), new((long)x + 4800, (long)y + 4700)], false, VectorPathKind.Outline, string.Empty, $"mark {part}"));
        }

        var shuffled = paths.OrderBy(_ => random.Next()).ToList();

        var order = PathOrderer.Order(shuffled, new StagePoint(0, 0));

        Assert.Equal(Shapes(shuffled), Shapes(order));
        for (var outer = 0; outer < order.Count; outer++)
        {
            for (var inner = 0; inner < order.Count; inner++)
            {
                if (inner != outer && order[outer].Closed && Encloses(order[outer], order[inner]))
                {
                    Assert.True(inner < outer, $"{order[inner].Source} (#{inner}) lies inside {order[outer].Source} (#{outer}) but comes after it");
                }
            }
        }
    }

    [Fact]
    public void Order_ClosedPath_StartsAtTheVertexNearestTheStart()
    {
        var square = Square(1000, 1000, 500);

        var order = PathOrderer.Order([square], new StagePoint(1600, 1600));

        Assert.Equal(new StagePoint(1500, 1500), order[0].Start);
        Assert.Equal(order[0].Start, order[0].End);
        Assert.Equal(square.Points.Take(4).ToHashSet(), order[0].Points.ToHashSet());
    }

    [Fact]
    public void Order_OpenPath_BurnsFromTheNearerEnd()
    {
        var line = new StagePath([new(0, 0), new(100, 0), new(1000, 0)], false, VectorPathKind.Outline, string.Empty, "line");

        var order = PathOrderer.Order([line], new StagePoint(1100, 0));

        Assert.Equal([new(1000, 0), new(100, 0), new(0, 0)], order[0].Points);
    }

    [Fact]
    public void Order_RowOfShapesDrawnShuffled_VisitsThemInARow()
    {
        // Ten squares on a line, drawn in a scrambled order: the shortest tour from the left visits them left to right.
        var squares = new[] { 7, 2, 9, 0, 5, 3, 8, 1, 6, 4 }.Select(i => Square(i * 1000, 0, 100)).ToList();

        var order = PathOrderer.Order(squares, new StagePoint(0, 0));

        Assert.Equal(Enumerable.Range(0, 10).Select(i => i * 1000L), order.Select(p => p.Points.Min(q => q.X)));
        Assert.True(PathOrderer.Travel(order, new StagePoint(0, 0)) < 10 * 1000);
    }

    private static StagePath Square(double x, double y, double size)
    {
        long x0 = (long)x, y0 = (long)y, s = (long)size;
        return new StagePath([new(x0, y0), new(x0 + s, y0), new(x0 + s, y0 + s), new(x0, y0 + s), new(x0, y0)], true, VectorPathKind.Outline, string.Empty, $"square at {x0},{y0}");
    }

    private static StagePath Circle(double cx, double cy, double r)
    {
        var points = Enumerable.Range(0, 33).Select(i => new StagePoint((long)Math.Round(cx + (r * Math.Cos(i * Math.PI / 16))), (long)Math.Round(cy + (r * Math.Sin(i * Math.PI / 16))))).ToList();
        points[^1] = points[0];
        return new StagePath(points, true, VectorPathKind.Outline, string.Empty, $"circle at {cx},{cy}");
    }

    /// <summary>Each path as the set of its vertices, so order, start and direction do not matter.</summary>
    private static List<string> Shapes(IEnumerable<StagePath> paths) =>
        [.. paths.Select(p => string.Join(";", p.Points.Distinct().OrderBy(q => q.X).ThenBy(q => q.Y))).Order(StringComparer.Ordinal)];

    private static List<string> Shapes(VectorPlan plan) => Shapes(plan.Paths);

    /// <summary>Whether every vertex of <paramref name="inner"/> is strictly inside <paramref name="outer"/> (ray casting).</summary>
    private static bool Encloses(StagePath outer, StagePath inner) => inner.Points.All(p => Inside(outer.Points, p.X, p.Y));

    private static bool Inside(IReadOnlyList<StagePoint> ring, double x, double y)
    {
        var inside = false;
        for (int i = 0, j = ring.Count - 2; i < ring.Count - 1; j = i++)
        {
            if ((ring[i].Y > y) != (ring[j].Y > y) && x < ((ring[j].X - ring[i].X) * (y - ring[i].Y) / (double)(ring[j].Y - ring[i].Y)) + ring[i].X)
            {
                inside = !inside;
            }
        }

        return inside;
    }
}
