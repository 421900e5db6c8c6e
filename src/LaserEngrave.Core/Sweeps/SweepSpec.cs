using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Sweeps;

/// <summary>A parameter sweep: a grid of test cells, one or two process values varied over its rows and columns, burned in one run.</summary>
public sealed record SweepSpec
{
    public SweepPattern Pattern { get; init; } = SweepPattern.Square;

    /// <summary>The mask every cell burns with <see cref="SweepPattern.Image"/>, its larger side spanning the cell; null otherwise.</summary>
    public BitMask? CellImage { get; init; }

    /// <summary>Where <see cref="CellImage"/> came from (a file name), for the log and messages.</summary>
    public string? CellImageName { get; init; }

    /// <summary>Side of each (square) cell, mm.</summary>
    public double CellMm { get; init; } = 1;

    /// <summary>White between neighbouring cells, mm.</summary>
    public double SpacingMm { get; init; } = 0.5;

    /// <summary>Stage position of the grid's top-left corner (its labels' when there are labels), mm.</summary>
    public OriginMm Origin { get; init; } = new(1, 1);

    /// <summary>The cells' pixel pitch, µm, unless the sweep varies it.</summary>
    public double PitchUm { get; init; } = 50;

    /// <summary>The parameter varied down the rows, one value a row.</summary>
    public required SweepAxis Rows { get; init; }

    /// <summary>The option that gave <see cref="Rows"/>, as error lines name it (<c>--focus-um</c> for a focal series).</summary>
    public string RowsOption { get; init; } = "--rows";

    /// <summary>The parameter varied across the columns, one value a column; null: one column.</summary>
    public SweepAxis? Columns { get; init; }

    /// <summary>Burn each row's and column's value beside it in a tiny font (raster, at the base process).</summary>
    public bool Labels { get; init; }

    /// <summary>The process of every cell before the sweep's values are put in (and of the labels).</summary>
    public ProcessSettings Process { get; init; } = ProcessSettings.Default;

    public PlanOptions Plan { get; init; } = PlanOptions.Default;

    public MachineProfile Profile { get; init; } = MachineProfile.Default;

    /// <summary>Passes of every cell unless the sweep varies them.</summary>
    public int Passes { get; init; } = 1;
}
