using System.Globalization;

namespace LaserEngrave.Core.Vectors;

/// <summary>Parses SVG path data (the d attribute) into subpaths: every command, absolute and relative, with implicit repeats and elliptical arcs.</summary>
internal sealed class SvgPathData
{
    private readonly string _d;
    private readonly string _element;
    private int _pos;

    private SvgPathData(string d, string element)
    {
        _d = d;
        _element = element;
    }

    /// <summary>The subpaths of <paramref name="d"/>, in user units; <paramref name="element"/> names the element in errors.</summary>
    public static List<(List<IDrawingCurve> Curves, bool Closed)> Parse(string d, string element) => new SvgPathData(d, element).Run();

    /// <summary>The SVG arc from p0 to p1 (SVG 1.1 appendix F.6.5: endpoint to centre parametrisation, radii scaled up when too small).</summary>
    public static IDrawingCurve? Arc(DrawingPoint p0, double rx, double ry, double angleDegrees, bool large, bool sweep, DrawingPoint p1)
    {
        if (p0 == p1)
        {
            return null;
        }

        rx = Math.Abs(rx);
        ry = Math.Abs(ry);
        if (rx == 0 || ry == 0)
        {
            return new LineCurve(p0, p1);
        }

        var phi = angleDegrees * Math.PI / 180;
        double cos = Math.Cos(phi), sin = Math.Sin(phi);
        double dx = (p0.X - p1.X) / 2, dy = (p0.Y - p1.Y) / 2;
        double x1 = (cos * dx) + (sin * dy), y1 = (-sin * dx) + (cos * dy);
        var lambda = (x1 * x1 / (rx * rx)) + (y1 * y1 / (ry * ry));
        if (lambda > 1)
        {
            rx *= Math.Sqrt(lambda);
            ry *= Math.Sqrt(lambda);
        }

        var numerator = (rx * rx * ry * ry) - (rx * rx * y1 * y1) - (ry * ry * x1 * x1);
        var denominator = (rx * rx * y1 * y1) + (ry * ry * x1 * x1);
        var coefficient = (large != sweep ? 1 : -1) * Math.Sqrt(Math.Max(0, numerator / denominator));
        double cx1 = coefficient * rx * y1 / ry, cy1 = -coefficient * ry * x1 / rx;
        var center = new DrawingPoint((cos * cx1) - (sin * cy1) + ((p0.X + p1.X) / 2), (sin * cx1) + (cos * cy1) + ((p0.Y + p1.Y) / 2));
        var theta1 = Math.Atan2((y1 - cy1) / ry, (x1 - cx1) / rx);
        var theta2 = Math.Atan2((-y1 - cy1) / ry, (-x1 - cx1) / rx);
        var delta = theta2 - theta1;
        if (sweep && delta < 0)
        {
            delta += 2 * Math.PI;
        }
        else if (!sweep && delta > 0)
        {
            delta -= 2 * Math.PI;
        }

        return new EllipticalArcCurve(center, new DrawingPoint(rx * cos, rx * sin), new DrawingPoint(-ry * sin, ry * cos), theta1, delta, p0, p1);
    }

    private List<(List<IDrawingCurve>, bool)> Run()
    {
        var subpaths = new List<(List<IDrawingCurve>, bool)>();
        List<IDrawingCurve>? curves = null;
        DrawingPoint current = default, subpathStart = default, lastControl = default;
        var command = '\0';
        var previous = '\0';
        SkipSeparators();
        if (_pos < _d.Length && char.ToUpperInvariant(_d[_pos]) != 'M')
        {
            throw Error("path data must begin with M (moveto)");
        }

        while (SkipSeparators())
        {
            if (char.IsLetter(_d[_pos]))
            {
                command = _d[_pos++];
                if ("MmLlHhVvCcSsQqTtAaZz".IndexOf(command, StringComparison.Ordinal) < 0)
                {
                    _pos--;
                    throw Error($"'{command}' is not a path command");
                }
            }
            else if (command is '\0' or 'Z' or 'z')
            {
                throw Error("a number where a command was expected");
            }

            var relative = char.IsLower(command);
            var origin = relative ? current : default;
            switch (char.ToUpperInvariant(command))
            {
                case 'M':
                    Finish(false);
                    current = origin + Point();
                    subpathStart = current;
                    curves = [];

                    // Further coordinate pairs after a moveto are implicit linetos.
                    command = relative ? 'l' : 'L';
                    break;
                case 'L':
                    LineTo(origin + Point());
                    break;
                case 'H':
                    LineTo(new DrawingPoint(Number() + (relative ? current.X : 0), current.Y));
                    break;
                case 'V':
                    LineTo(new DrawingPoint(current.X, Number() + (relative ? current.Y : 0)));
                    break;
                case 'C':
                {
                    var c1 = origin + Point();
                    var c2 = origin + Point();
                    var end = origin + Point();
                    Add(new BezierCurve(current, c1, c2, end), end, c2);
                    break;
                }

                case 'S':
                {
                    var c1 = previous is 'C' or 'S' ? (current * 2) - lastControl : current;
                    var c2 = origin + Point();
                    var end = origin + Point();
                    Add(new BezierCurve(current, c1, c2, end), end, c2);
                    break;
                }

                case 'Q':
                {
                    var c = origin + Point();
                    var end = origin + Point();
                    Add(new BezierCurve(current, c, end), end, c);
                    break;
                }

                case 'T':
                {
                    var c = previous is 'Q' or 'T' ? (current * 2) - lastControl : current;
                    var end = origin + Point();
                    Add(new BezierCurve(current, c, end), end, c);
                    break;
                }

                case 'A':
                {
                    double rx = Number(), ry = Number(), angle = Number();
                    bool large = Flag(), sweep = Flag();
                    var end = origin + Point();
                    var arc = Arc(current, rx, ry, angle, large, sweep, end);
                    if (arc is not null)
                    {
                        curves!.Add(arc);
                    }

                    current = end;
                    lastControl = end;
                    break;
                }

                case 'Z':
                    if (current != subpathStart)
                    {
                        curves!.Add(new LineCurve(current, subpathStart));
                    }

                    Finish(true);
                    current = subpathStart;

                    // A drawing command after Z starts a new subpath at the same point.
                    curves = [];
                    break;
            }

            previous = char.ToUpperInvariant(command);
        }

        Finish(false);
        return subpaths;

        void LineTo(DrawingPoint end)
        {
            if (end != current)
            {
                curves!.Add(new LineCurve(current, end));
            }

            current = end;
            lastControl = end;
        }

        void Add(IDrawingCurve curve, DrawingPoint end, DrawingPoint control)
        {
            if (curve.Start != end || control != end)
            {
                curves!.Add(curve);
            }

            current = end;
            lastControl = control;
        }

        void Finish(bool closed)
        {
            if (curves is { Count: > 0 })
            {
                subpaths.Add((curves, closed || curves[0].Start == curves[^1].End));
            }

            curves = null;
        }
    }

    private DrawingPoint Point() => new(Number(), Number());

    private bool SkipSeparators()
    {
        while (_pos < _d.Length && (char.IsWhiteSpace(_d[_pos]) || _d[_pos] == ','))
        {
            _pos++;
        }

        return _pos < _d.Length;
    }

    private bool Flag()
    {
        if (!SkipSeparators() || _d[_pos] is not ('0' or '1'))
        {
            throw Error("an arc flag (0 or 1) was expected");
        }

        return _d[_pos++] == '1';
    }

    private double Number()
    {
        if (!SkipSeparators())
        {
            throw Error("the path data ends in the middle of a command");
        }

        var start = _pos;
        if (_d[_pos] is '+' or '-')
        {
            _pos++;
        }

        var digits = 0;
        while (_pos < _d.Length && char.IsAsciiDigit(_d[_pos]))
        {
            _pos++;
            digits++;
        }

        if (_pos < _d.Length && _d[_pos] == '.')
        {
            _pos++;
            while (_pos < _d.Length && char.IsAsciiDigit(_d[_pos]))
            {
                _pos++;
                digits++;
            }
        }

        if (digits > 0 && _pos < _d.Length && _d[_pos] is 'e' or 'E')
        {
            var mark = _pos++;
            if (_pos < _d.Length && _d[_pos] is '+' or '-')
            {
                _pos++;
            }

            if (_pos < _d.Length && char.IsAsciiDigit(_d[_pos]))
            {
                while (_pos < _d.Length && char.IsAsciiDigit(_d[_pos]))
                {
                    _pos++;
                }
            }
            else
            {
                _pos = mark;
            }
        }

        if (digits == 0 || !double.TryParse(_d.AsSpan(start, _pos - start), NumberStyles.Float, CultureInfo.InvariantCulture, out var value) || !double.IsFinite(value))
        {
            _pos = start;
            throw Error("a number was expected");
        }

        return value;
    }

    private DrawingException Error(string problem)
    {
        var near = _d.Substring(_pos, Math.Min(12, _d.Length - _pos));
        return new DrawingException($"{_element}: path data at character {_pos + 1}{(near.Length > 0 ? $" (\"{near}\")" : string.Empty)}: {problem}");
    }
}
