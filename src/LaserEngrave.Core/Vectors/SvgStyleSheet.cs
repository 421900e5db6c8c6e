using System.Text.RegularExpressions;
using System.Xml;
using System.Xml.Linq;

namespace LaserEngrave.Core.Vectors;

/// <summary>
/// The rules of an SVG's &lt;style&gt; elements that change what is burned: <c>display</c> and <c>visibility</c>, for
/// simple selectors (<c>path</c>, <c>.class</c>, <c>#id</c>, <c>path.class</c>, <c>*</c>, comma lists). A rule that
/// sets either with a selector it cannot apply (descendants, children, attributes, pseudo-classes, @media) is refused
/// naming it, so geometry hidden or shown by CSS is never burned other than the drawing shows. Stroke and fill do not
/// change what is burned (every visible outline is), so rules that only set them are read past.
/// </summary>
internal sealed partial class SvgStyleSheet
{
    private readonly List<Rule> _rules = [];

    private SvgStyleSheet()
    {
    }

    /// <summary>The rules of every &lt;style&gt; in <paramref name="document"/>; throws <see cref="DrawingException"/> for one it cannot apply.</summary>
    public static SvgStyleSheet Read(XDocument document, string path)
    {
        var sheet = new SvgStyleSheet();
        var order = 0;
        foreach (var style in document.Descendants().Where(e => e.Name.LocalName == "style"))
        {
            var line = ((IXmlLineInfo)style).HasLineInfo() ? $" (line {((IXmlLineInfo)style).LineNumber})" : string.Empty;
            var css = Comments().Replace(style.Value, " ");
            if (css.Contains('@', StringComparison.Ordinal) && Drawn().IsMatch(css))
            {
                throw new DrawingException($"{path}: <style>{line}: at-rules (@media, @import, @supports) are not applied, and the style sets display or visibility; move those rules out of the at-rule or set display on the elements");
            }

            foreach (Match rule in Rules().Matches(css))
            {
                var selectors = rule.Groups["selectors"].Value.Trim();
                var declarations = Declarations(rule.Groups["body"].Value).Where(d => d.Property is "display" or "visibility").ToList();
                if (declarations.Count == 0)
                {
                    continue;
                }

                foreach (var text in selectors.Split(',', StringSplitOptions.TrimEntries | StringSplitOptions.RemoveEmptyEntries))
                {
                    var selector = Simple().Match(text);
                    if (!selector.Success)
                    {
                        throw new DrawingException(
                            $"{path}: <style>{line}: the rule \"{text} {{ {string.Join("; ", declarations.Select(d => $"{d.Property}: {d.Value}"))} }}\" cannot be applied: LaserEngrave applies display and visibility for selectors of one element (type, .class, #id, or both, or *); simplify the selector or set display on the elements");
                    }

                    var type = selector.Groups["type"].Value;
                    var id = selector.Groups["id"].Success ? selector.Groups["id"].Value : null;
                    var classes = selector.Groups["class"].Captures.Select(c => c.Value).ToArray();
                    var specificity = ((id is null ? 0 : 1) * 10000) + (classes.Length * 100) + (type is "" or "*" ? 0 : 1);
                    foreach (var (property, value) in declarations)
                    {
                        sheet._rules.Add(new Rule(type is "" or "*" ? null : type, id, classes, property, value, specificity, order++));
                    }
                }
            }
        }

        return sheet;
    }

    /// <summary>The value the style sheet gives <paramref name="property"/> on <paramref name="e"/>, or null when no rule matches.</summary>
    public string? Value(XElement e, string property)
    {
        if (_rules.Count == 0)
        {
            return null;
        }

        var id = e.Attribute("id")?.Value;
        var classes = (e.Attribute("class")?.Value ?? string.Empty).Split([' ', '\t', '\n', '\r'], StringSplitOptions.RemoveEmptyEntries);
        Rule? best = null;
        foreach (var rule in _rules)
        {
            if (rule.Property == property
                && (rule.Type is null || rule.Type == e.Name.LocalName)
                && (rule.Id is null || rule.Id == id)
                && rule.Classes.All(c => classes.Contains(c, StringComparer.Ordinal))
                && (best is null || rule.Specificity > best.Specificity || (rule.Specificity == best.Specificity && rule.Order > best.Order)))
            {
                best = rule;
            }
        }

        return best?.Value;
    }

    /// <summary>"a: b; c: d" as (property, value) pairs, lower case, !important left out.</summary>
    public static IEnumerable<(string Property, string Value)> Declarations(string text)
    {
        foreach (var declaration in text.Split(';'))
        {
            var parts = declaration.Split(':', 2);
            if (parts.Length == 2)
            {
                yield return (parts[0].Trim().ToLowerInvariant(), parts[1].Replace("!important", string.Empty, StringComparison.OrdinalIgnoreCase).Trim().ToLowerInvariant());
            }
        }
    }

    [GeneratedRegex(@"/\*.*?\*/", RegexOptions.Singleline)]
    private static partial Regex Comments();

    [GeneratedRegex(@"(?<selectors>[^{}]+)\{(?<body>[^{}]*)\}")]
    private static partial Regex Rules();

    [GeneratedRegex(@"\b(display|visibility)\s*:")]
    private static partial Regex Drawn();

    [GeneratedRegex(@"^(?<type>\*|[A-Za-z][\w-]*)?(?:#(?<id>[\w-]+))?(?:\.(?<class>[\w-]+))*$")]
    private static partial Regex Simple();

    private sealed record Rule(string? Type, string? Id, string[] Classes, string Property, string Value, int Specificity, int Order);
}
