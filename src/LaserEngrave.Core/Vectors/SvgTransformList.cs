using System.Globalization;
using System.Text.RegularExpressions;

namespace LaserEngrave.Core.Vectors;

/// <summary>Parses an SVG transform attribute: matrix, translate, scale, rotate (about a point too), skewX and skewY, applied right to left.</summary>
internal static partial class SvgTransformList
{
    public static Affine Parse(string text, string element)
    {
        var result = Affine.Identity;
        var end = 0;
        var transforms = new List<Affine>();
        foreach (Match m in Function().Matches(text))
        {
            if (text[end..m.Index].Any(c => !char.IsWhiteSpace(c) && c != ','))
            {
                throw Error();
            }

            end = m.Index + m.Length;
            var name = m.Groups[1].Value;
            var args = Numbers().Matches(m.Groups[2].Value).Select(n => double.Parse(n.Value, NumberStyles.Float, CultureInfo.InvariantCulture)).ToArray();
            if (Numbers().Replace(m.Groups[2].Value, string.Empty).Any(c => !char.IsWhiteSpace(c) && c != ','))
            {
                throw Error();
            }

            transforms.Add((name, args.Length) switch
            {
                ("matrix", 6) => new Affine(args[0], args[1], args[2], args[3], args[4], args[5]),
                ("translate", 1) => Affine.Translate(args[0], 0),
                ("translate", 2) => Affine.Translate(args[0], args[1]),
                ("scale", 1) => Affine.Scale(args[0], args[0]),
                ("scale", 2) => Affine.Scale(args[0], args[1]),
                ("rotate", 1) => Affine.Rotate(args[0]),
                ("rotate", 3) => Affine.Compose(Affine.Compose(Affine.Translate(-args[1], -args[2]), Affine.Rotate(args[0])), Affine.Translate(args[1], args[2])),
                ("skewX", 1) => Affine.SkewX(args[0]),
                ("skewY", 1) => Affine.SkewY(args[0]),
                _ => throw new DrawingException($"{element}: transform {name}({m.Groups[2].Value.Trim()}): wrong number of values ({args.Length})"),
            });
        }

        if (text[end..].Any(c => !char.IsWhiteSpace(c) && c != ','))
        {
            throw Error();
        }

        // "a b" means a applied to (b applied to the point): the rightmost acts first.
        for (var i = transforms.Count - 1; i >= 0; i--)
        {
            result = Affine.Compose(result, transforms[i]);
        }

        return result;

        DrawingException Error() => new($"{element}: transform \"{text}\" is not a list of matrix, translate, scale, rotate, skewX or skewY");
    }

    [GeneratedRegex(@"(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)")]
    private static partial Regex Function();

    [GeneratedRegex(@"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")]
    private static partial Regex Numbers();
}
