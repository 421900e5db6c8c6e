using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Marks;

/// <summary>A code drawn into a burn mask at a pixel pitch the spot fills: whole pixels a module, the quiet zone white around it.</summary>
/// <param name="Symbol">The code.</param>
/// <param name="Mask">Set = burn; the quiet zone included.</param>
/// <param name="PixelsPerModule">Mask pixels along a module's side.</param>
/// <param name="ModuleUm">A module's side.</param>
/// <param name="QuietModules">White modules around the code on every side.</param>
public sealed record CodeRaster(CodeSymbol Symbol, BitMask Mask, int PixelsPerModule, double ModuleUm, int QuietModules)
{
    /// <summary>A mask pixel's side, µm: the rows' pitch, at most the spot's diameter so that rows overlap and a module is filled.</summary>
    public double PitchUm => ModuleUm / PixelsPerModule;

    /// <summary>The whole mask's side with its quiet zone, mm.</summary>
    public double WidthMm => Units.StepsToMm(Mask.Width, PitchUm);

    /// <summary>The code's side without its quiet zone, mm.</summary>
    public double SymbolMm => Units.StepsToMm(Symbol.Size, ModuleUm);

    /// <summary>Draws <paramref name="symbol"/> with modules of <paramref name="moduleUm"/>; refuses a module the spot cannot resolve.</summary>
    /// <exception cref="MarkException">The module is smaller than the spot or larger than a sane mark, or the quiet zone is out of range.</exception>
    public static CodeRaster Render(CodeSymbol symbol, double moduleUm, int quietModules, double spotDiameterUm)
    {
        ArgumentNullException.ThrowIfNull(symbol);
        if (RefusedModule(moduleUm, spotDiameterUm) is { } problem)
        {
            throw new MarkException(problem);
        }

        if (quietModules is < 0 or > 10)
        {
            throw new MarkException($"quiet zone {quietModules} modules must be 0..10");
        }

        var perModule = Math.Max(1, (int)Math.Ceiling((moduleUm / spotDiameterUm) - 1e-9));
        var side = (symbol.Size + (2 * quietModules)) * perModule;
        var mask = new BitMask(side, side);
        for (var my = 0; my < symbol.Size; my++)
        {
            for (var mx = 0; mx < symbol.Size; mx++)
            {
                if (!symbol.Modules[mx, my])
                {
                    continue;
                }

                for (var j = 0; j < perModule; j++)
                {
                    for (var i = 0; i < perModule; i++)
                    {
                        mask[((mx + quietModules) * perModule) + i, ((my + quietModules) * perModule) + j] = true;
                    }
                }
            }
        }

        return new CodeRaster(symbol, mask, perModule, moduleUm, quietModules);
    }

    /// <summary>Why a module of <paramref name="moduleUm"/> cannot be burned with a spot of <paramref name="spotDiameterUm"/>, or null when it can be tried.</summary>
    public static string? RefusedModule(double moduleUm, double spotDiameterUm)
    {
        if (!(moduleUm > 0 && double.IsFinite(moduleUm)))
        {
            return string.Create(CultureInfo.InvariantCulture, $"module {moduleUm:G6} µm must be a finite number above 0");
        }

        if (moduleUm > 10_000)
        {
            return string.Create(CultureInfo.InvariantCulture, $"module {moduleUm:G6} µm is larger than 10 mm");
        }

        // A module narrower than the spot is burned together with its white neighbours: the code cannot come out.
        return moduleUm < spotDiameterUm
            ? string.Create(CultureInfo.InvariantCulture, $"module {moduleUm:0.#} µm is smaller than the spot's {spotDiameterUm:0.#} µm diameter, which cannot resolve it; make the mark larger or its text shorter")
            : null;
    }
}
