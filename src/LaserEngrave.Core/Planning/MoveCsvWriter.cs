using System.Globalization;

namespace LaserEngrave.Core.Planning;

/// <summary>Writes a plan's moves as CSV: header <c>kind,x0,y0,x1,y1</c>, kind <c>burn</c> or <c>travel</c> (overscan is written as travel), positions in microsteps.</summary>
public static class MoveCsvWriter
{
    public const string Header = "kind,x0,y0,x1,y1";

    /// <summary>Writes every move of <paramref name="plan"/>, streaming.</summary>
    public static void Write(RasterPlan plan, TextWriter writer)
    {
        ArgumentNullException.ThrowIfNull(plan);
        ArgumentNullException.ThrowIfNull(writer);
        writer.Write(Header);
        writer.Write('\n');
        var visitor = new LineVisitor(writer);
        plan.Visit(ref visitor);
    }

    /// <summary>Writes every move of <paramref name="plan"/> to the file at <paramref name="path"/>.</summary>
    public static void Write(RasterPlan plan, string path)
    {
        using var writer = new StreamWriter(path, append: false, new System.Text.UTF8Encoding(encoderShouldEmitUTF8Identifier: false), bufferSize: 1 << 16);
        Write(plan, writer);
    }

    /// <summary>Formats one move as a CSV line without the line end.</summary>
    public static string FormatLine(in Move move) =>
        string.Create(CultureInfo.InvariantCulture, $"{KindName(move.Kind)},{move.X0},{move.Y0},{move.X1},{move.Y1}");

    private static string KindName(MoveKind kind) => kind == MoveKind.Burn ? "burn" : "travel";

    private readonly struct LineVisitor(TextWriter writer) : IMoveVisitor
    {
        private readonly char[] _line = new char[5 * 21];

        public void Visit(in Move move)
        {
            var span = _line.AsSpan();
            var kind = KindName(move.Kind);
            kind.CopyTo(span);
            var n = kind.Length;
            foreach (var value in (ReadOnlySpan<long>)[move.X0, move.Y0, move.X1, move.Y1])
            {
                span[n++] = ',';
                value.TryFormat(span[n..], out var written, provider: CultureInfo.InvariantCulture);
                n += written;
            }

            span[n++] = '\n';
            writer.Write(_line, 0, n);
        }
    }
}
